#!/usr/bin/env bash
# Starts `gearsph serve` on a scratch data directory, runs the load benchmark
# (bench/server_load.cpp) against it while a job runs, then stops the server.
#   bench/server_load.sh [BUILD_DIR] [--connections N] [--seconds S] [--jobs J] ...
# BUILD_DIR defaults to build/ (it needs gearsph and bench/gearsph_server_load).
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then build=$1; shift; fi
scratch=$(mktemp -d)
"$build/gearsph" serve --port 0 --data "$scratch/data" >"$scratch/serve.out" 2>"$scratch/serve.err" &
pid=$!
trap 'kill -TERM $pid 2>/dev/null || true; wait $pid 2>/dev/null || true; rm -rf "$scratch"' EXIT
for _ in $(seq 100); do
  grep -q "listening on" "$scratch/serve.out" 2>/dev/null && break
  sleep 0.1
done
url=$(grep -o 'http://[0-9.]*:[0-9]*' "$scratch/serve.out" | head -n1)
if [ -z "$url" ]; then
  cat "$scratch/serve.err" >&2
  exit 1
fi
"$build/bench/gearsph_server_load" --server "$url" "$@"
