# Sourced by the engine scripts of the scale-out tests (postgres.sh,
# slurm.sh), which set $script (their own path) and $dir (the engine's
# directory).
#
# With GEARSPH_ENGINE_OWNER=PID (the tests set it), a watchdog stops the
# engine once that process is gone, so a test killed by a timeout leaves no
# daemon behind.
start_watchdog() {
  [ -n "${GEARSPH_ENGINE_OWNER:-}" ] || return 0
  setsid sh -c 'while kill -0 "$1" 2>/dev/null; do sleep 1; done; exec "$2" stop "$3"' \
    watchdog "$GEARSPH_ENGINE_OWNER" "$script" "$dir" </dev/null >/dev/null 2>&1 &
  echo $! >"$dir/watchdog.pid"
}
stop_watchdog() {
  [ -s "$dir/watchdog.pid" ] || return 0
  local pid
  pid=$(cat "$dir/watchdog.pid")
  rm -f "$dir/watchdog.pid"
  [ "$pid" = "$$" ] || kill "$pid" 2>/dev/null || true
}
