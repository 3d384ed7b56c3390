#!/usr/bin/env bash
# The README's walkthrough with curl ("The service with curl"), run as it is
# written against a real server on loopback:
#   - with a job the server refuses (a typo in the scene type), it stops at
#     once with the server's answer: no endless event stream of every job, no
#     problem document saved as von_mises.png;
#   - with a short job, it ends with the results and a PNG.
# usage: readme_curl.sh GEARSPH README.md
set -uo pipefail
GEARSPH=$1
README=$2
work=$(mktemp -d)
server=""
cleanup() {
  if [ -n "$server" ]; then kill "$server" 2>/dev/null; wait "$server" 2>/dev/null; fi
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$GEARSPH" serve --port 0 --data "$work/data" --threads-per-job 1 >"$work/serve.out" 2>"$work/serve.err" &
server=$!
for _ in $(seq 300); do
  port=$(sed -n 's/.*listening on http:\/\/127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/serve.out")
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || fail "the server did not start: $(cat "$work/serve.err")"

# The first sh block after the section's heading.
block=$(awk '/^## The service with curl/ {in_section = 1}
             in_section && /^```sh/ {in_block = 1; next}
             in_block && /^```/ {exit}
             in_block {print}' "$README")
[ -n "$block" ] || fail "no curl block in $README"
block=${block//127.0.0.1:8080/127.0.0.1:$port}

run() {  # run DIR SCRIPT: the walkthrough in DIR, at most 120 s
  mkdir -p "$1"
  (cd "$1" && timeout 120 bash -c "$2" >out.txt 2>err.txt)
}

# A refused job: the walkthrough stops, with the problem and the status shown.
refused=${block/\"rack_pinion\"/\"rack_pinon\"}
[ "$refused" != "$block" ] || fail "the walkthrough's job is not the rack-and-pinion case"
run "$work/refused" "$refused"
status=$?
[ "$status" -ne 124 ] || fail "a refused job left the walkthrough running (an endless stream?)"
[ "$status" -ne 0 ] || fail "a refused job did not stop the walkthrough"
grep -q '"status": 400' "$work/refused/out.txt" || fail "the refusal is not shown: $(cat "$work/refused/out.txt")"
grep -q '400' "$work/refused/err.txt" || fail "the status is not shown: $(cat "$work/refused/err.txt")"
[ ! -e "$work/refused/von_mises.png" ] || fail "a refusal was saved as von_mises.png"
echo "ok: a refused job stops the walkthrough with the server's answer and status"

# A short job: results and a picture.
short=${block/\"end_s\": 0.002/\"end_s\": 0.00002}
[ "$short" != "$block" ] || fail "the walkthrough's job has no end time 0.002 to shorten"
run "$work/short" "$short" || fail "the walkthrough failed: $(cat "$work/short/err.txt")"
grep -q '"successful"' "$work/short/out.txt" || fail "no final status in the stream"
grep -q '"summary"' "$work/short/out.txt" || fail "no results"
[ "$(head -c 4 "$work/short/von_mises.png" | tail -c 3)" = "PNG" ] || fail "von_mises.png is not a PNG"
echo "ok: a short job ends with its results and a PNG"
