#!/usr/bin/env bash
# A throw-away PostgreSQL server on loopback, for the scale-out tests and for
# trying `gearsph worker` by hand (docs/scale-out.md).
#
#   tests/scaleout/postgres.sh start DIR [PORT]   # prints the store URI
#   tests/scaleout/postgres.sh restart DIR        # fast restart, same port
#   tests/scaleout/postgres.sh down DIR           # the server stopped (an outage) ...
#   tests/scaleout/postgres.sh up DIR             # ... and started again, same port
#   tests/scaleout/postgres.sh stop DIR
#
# The cluster lives in DIR/pg and listens on 127.0.0.1:PORT (a free port if
# not given) and a unix socket in DIR/pg; trust authentication, for loopback
# only. PostgreSQL refuses to run as root: as root, the server runs as the
# Debian `postgres` user (DIR is made world-traversable for it), otherwise as
# the calling user.
set -euo pipefail
cmd=${1:?usage: postgres.sh start|restart|down|up|stop DIR [PORT]}
dir=${2:?usage: postgres.sh start|restart|down|up|stop DIR [PORT]}
script=$(cd "$(dirname "$0")" && pwd)/$(basename "$0")

# The engine watchdog (start_watchdog, stop_watchdog) needs $script and $dir.
source "$(dirname "$script")/watchdog.sh"
bin=${PG_BIN:-$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -n 1)}
if [ -z "$bin" ] || [ ! -x "$bin/initdb" ]; then
  echo "postgres.sh: no PostgreSQL server binaries (apt-get install postgresql)" >&2
  exit 3
fi

as_owner() {
  if [ "$(id -u)" -eq 0 ]; then runuser -u postgres -- "$@"; else "$@"; fi
}

pg_options() {
  echo "-c listen_addresses=127.0.0.1 -p $(cat "$dir/port") -k $dir/pg -c max_connections=200"
}

case $cmd in
start)
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  port=${3:-$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')}
  echo "$port" >"$dir/port"
  if [ "$(id -u)" -eq 0 ]; then
    chmod 755 "$dir"
    mkdir -p "$dir/pg" && chown postgres: "$dir/pg" && chmod 700 "$dir/pg"
  fi
  as_owner "$bin/initdb" -D "$dir/pg" -A trust -U gearsph -E UTF8 --no-sync >"$dir/initdb.log" 2>&1 ||
    { cat "$dir/initdb.log" >&2; exit 1; }
  as_owner "$bin/pg_ctl" -D "$dir/pg" -l "$dir/pg/server.log" -w -t 60 -o "$(pg_options)" start \
    >/dev/null || { cat "$dir/pg/server.log" >&2; exit 1; }
  as_owner "$bin/createdb" -h 127.0.0.1 -p "$port" -U gearsph gearsph
  start_watchdog
  echo "postgresql://gearsph@127.0.0.1:$port/gearsph" | tee "$dir/uri"
  ;;
restart)
  dir=$(cd "$dir" && pwd)
  as_owner "$bin/pg_ctl" -D "$dir/pg" -m fast -w -t 60 -o "$(pg_options)" restart >/dev/null
  ;;
down)
  dir=$(cd "$dir" && pwd)
  as_owner "$bin/pg_ctl" -D "$dir/pg" -m immediate -w -t 60 stop >/dev/null
  ;;
up)
  dir=$(cd "$dir" && pwd)
  as_owner "$bin/pg_ctl" -D "$dir/pg" -l "$dir/pg/server.log" -w -t 60 -o "$(pg_options)" start \
    >/dev/null || { cat "$dir/pg/server.log" >&2; exit 1; }
  ;;
stop)
  if [ -d "$dir/pg" ]; then
    dir=$(cd "$dir" && pwd)
    stop_watchdog
    as_owner "$bin/pg_ctl" -D "$dir/pg" -m immediate -w -t 60 stop >/dev/null 2>&1 || true
  fi
  ;;
*)
  echo "usage: postgres.sh start|restart|down|up|stop DIR [PORT]" >&2
  exit 2
  ;;
esac
