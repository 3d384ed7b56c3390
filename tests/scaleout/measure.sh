#!/usr/bin/env bash
# Throughput of N `gearsph worker` processes on one PostgreSQL store against
# one, and the per-job cost of going through the store (docs/scale-out.md).
#
#   tests/scaleout/measure.sh [BUILD_DIR] [--jobs K] [--end-s T] [--workers "1 2 3"]
#
# Starts a throw-away PostgreSQL (tests/scaleout/postgres.sh) and, for each
# N, an API process without workers and N workers with one thread each; then
# submits K identical plate jobs through the API. The store's own clock
# times them: from the first job's creation to the last one's end
# (makespan), the gap a worker leaves between finishing a job and starting
# the next (claiming through the store), and the time a worker spends on a
# job beyond the solver's time loop. The same K jobs run back to back with
# `gearsph run --threads 1` give the time of the work alone.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$root/build
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then build=$(cd "$1" && pwd); shift; fi
jobs=24
end_s=0.02
counts="1 2 3"
while [ $# -gt 0 ]; do
  case $1 in
  --jobs) jobs=$2; shift 2 ;;
  --end-s) end_s=$2; shift 2 ;;
  --workers) counts=$2; shift 2 ;;
  *) echo "measure.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
gearsph=$build/gearsph
scratch=$(mktemp -d /tmp/gearsph-measure-XXXXXX)
chmod 755 "$scratch"  # as root, PostgreSQL runs as `postgres` and must reach its directory
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  "$root/tests/scaleout/postgres.sh" stop "$scratch/pg" >/dev/null 2>&1 || true
  rm -rf "$scratch"
}
trap cleanup EXIT

job="{\"scene\": {\"type\": \"plate\", \"length_m\": 0.1, \"thickness_m\": 0.01}, \"discretization\": {\"spacing_m\": 0.002}, \"time\": {\"end_s\": $end_s}}"
echo "$job" >"$scratch/job.json"
now() { date +%s.%N; }
calc() { awk "BEGIN { print $* }"; }

printf 'machine: %s cores, load average before: %s\n' "$(nproc)" "$(cut -d' ' -f1-3 /proc/loadavg)"
printf 'job: plate 0.1 m x 0.01 m, spacing 2 mm, end_s %s; %d jobs per run\n' "$end_s" "$jobs"

# The work alone: K runs back to back, one thread, no store.
t0=$(now)
for i in $(seq "$jobs"); do
  "$gearsph" run "$scratch/job.json" --out "$scratch/direct/$i" --threads 1 --quiet
done
t1=$(now)
direct=$(calc "($t1 - $t0) / $jobs")
loop=$(for i in $(seq "$jobs"); do sed -n 's/^ *"wall_s": *\([0-9.e+-]*\).*/\1/p' "$scratch/direct/$i/summary.json"; done |
  awk '{ s += $1 } END { printf "%.3f", s / NR }')
printf '%-28s %6.3f s per job (%5.0f jobs/hour); time loop %s s of it\n' \
  'gearsph run, one by one:' "$direct" "$(calc "3600 / $direct")" "$loop"

uri=$("$root/tests/scaleout/postgres.sh" start "$scratch/pg" | tail -n 1)
sql() { psql "$uri" -At -F ' ' -c "$1"; }
for n in $counts; do
  results=$scratch/results-$n
  mkdir -p "$results"
  "$gearsph" serve --port 0 --data "$scratch/api-$n" --store "$uri" --no-local-workers \
    --results "$results" >"$scratch/api-$n.out" 2>"$scratch/api-$n.err" &
  pids+=($!)
  for _ in $(seq 200); do grep -q 'listening on' "$scratch/api-$n.out" 2>/dev/null && break; sleep 0.05; done
  url=$(sed -n 's/.*listening on \(http:\/\/[0-9.:]*\).*/\1/p' "$scratch/api-$n.out")
  for w in $(seq "$n"); do
    "$gearsph" worker --store "$uri" --results "$results" --threads-per-job 1 \
      >"$scratch/worker-$n-$w.out" 2>"$scratch/worker-$n-$w.err" &
    pids+=($!)
  done
  for _ in $(seq 200); do
    [ "$(cat "$scratch"/worker-"$n"-*.out 2>/dev/null | grep -c ' ready (')" = "$n" ] && break
    sleep 0.05
  done
  sql "DELETE FROM jobs" >/dev/null
  for i in $(seq "$jobs"); do
    curl -sf -o /dev/null -X POST "$url/jobs" -H 'Content-Type: application/json' -d "$job"
  done
  until [ "$(sql "SELECT COUNT(*) FROM jobs WHERE status IN ('accepted', 'running')")" = 0 ]; do
    sleep 0.2
  done
  # Everything from the store's timestamps (one clock, millisecond resolution).
  read -r makespan done_ok workers_used < <(sql "
    SELECT EXTRACT(EPOCH FROM MAX(finished::timestamptz) - MIN(created::timestamptz)),
           COUNT(*) FILTER (WHERE status = 'successful'), COUNT(DISTINCT worker) FROM jobs")
  read -r gap beyond < <(sql "
    WITH j AS (SELECT worker, started::timestamptz AS s, finished::timestamptz AS f, wall_s FROM jobs),
         g AS (SELECT EXTRACT(EPOCH FROM s - LAG(f) OVER (PARTITION BY worker ORDER BY s)) AS gap FROM j)
    SELECT (SELECT ROUND(AVG(gap)::numeric, 4) FROM g WHERE gap IS NOT NULL),
           (SELECT ROUND(AVG(EXTRACT(EPOCH FROM f - s) - wall_s)::numeric, 4) FROM j)")
  per=$(calc "$makespan / $jobs")
  printf '%d worker%s x 1 thread: %7.3f s per job (%5.0f jobs/hour, x%.2f of one worker)' \
    "$n" "$([ "$n" = 1 ] && echo ' ' || echo s)" "$per" "$(calc "3600 / $per")" "$(calc "${one:-$per} / $per")"
  printf '; %d/%d successful on %d workers; gap between jobs %s s; worker time beyond the loop %s s\n' \
    "$done_ok" "$jobs" "$workers_used" "$gap" "$beyond"
  if [ "$n" = 1 ]; then
    printf '  store overhead per job, one worker against gearsph run one by one: %.3f s\n' "$(calc "$per - $direct")"
  fi
  one=${one:-$per}
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  pids=()
done
printf 'load average after: %s\n' "$(cut -d' ' -f1-3 /proc/loadavg)"
