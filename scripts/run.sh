#!/usr/bin/env bash
# Sets up, builds, and runs the validation report of the solver.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
exec ./build/gearsph validate "$@"
