#!/usr/bin/env bash
# Sets up, builds and starts the job service with its dashboard on the
# embedded defaults (SQLite job store and results in ./data, loopback only).
# Extra arguments go to `gearsph serve` (e.g. --workers 2); GEARSPH_PORT
# chooses the port (default 8080).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
PORT="${GEARSPH_PORT:-8080}"
echo "run: dashboard at http://127.0.0.1:${PORT}/ (Ctrl-C stops the server; jobs in ./data)"
exec ./build/gearsph serve --port "$PORT" --data ./data "$@"
