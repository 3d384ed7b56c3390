#!/usr/bin/env bash
# Configures and builds GearSPH (Release) into build/; extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/compiler_cache.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${GEARSPH_CACHE_FLAGS[@]}" "$@" >/dev/null
cmake --build build
