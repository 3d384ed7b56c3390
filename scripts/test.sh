#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite: the Release build with every
# test, then an AddressSanitizer + UndefinedBehaviorSanitizer build running
# the unit tests (the long validation runs are too slow under sanitizers).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
(cd build && ctest --output-on-failure -j2)

cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DGEARSPH_SANITIZE=ON \
  -DGEARSPH_BENCH=OFF >/dev/null
cmake --build build-asan
# Debian's OSMesa leaks a few hundred bytes per GL context: suppressed, only that.
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/../tests/lsan.supp \
  ctest --output-on-failure -j2 -L unit -LE paraview)
echo "test: all tests passed"
