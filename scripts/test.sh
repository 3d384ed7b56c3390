#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite: the Release build with every
# test, then a sanitizer build of the solver and the results writer running
# their unit tests (the long validation runs are too slow under sanitizers).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
./scripts/build.sh
(cd build && ctest --output-on-failure -j2)

source scripts/compiler_cache.sh
# The sanitizer stage: the solver and the results writer under ASan
# (CMakeLists.txt), with their unit tests but for the few that take 10 s and
# more in Release, and those that build whole gear scenes (45-165 s each
# under ASan here, 940 s in all: Boost.Geometry's clipping), which run in the
# Release build above. At -O1, as the
# sanitizers' documentation advises, and portable (at -O1 GCC 12 warns,
# wrongly, of uninitialised values inside the AVX-512 intrinsics Eigen
# uses). The service, renderer and FE check are left out of this build: a
# second build of the Beast server alone takes over ten minutes on two
# cores, and with it the suite no longer fitted CI's half hour. Their
# sanitized build is one flag away (README, Build options).
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
  -DGEARSPH_SANITIZE=ON -DGEARSPH_NATIVE=OFF -DGEARSPH_BENCH=OFF -DGEARSPH_SERVICE=OFF \
  -DGEARSPH_RENDER=OFF -DGEARSPH_FE=OFF "${GEARSPH_CACHE_FLAGS[@]}" >/dev/null
cmake --build build-asan --target gearsph_tests
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/../tests/lsan.supp \
  ctest --output-on-failure -j2 -L unit -LE paraview \
    -E '^(TorqueDrive|GradedKernel|BodyFitted|ResultsCrash|RackBody|GradedScenes)\.|^GearCrack\.(Refuses|BackupRatio)|^ModelledTeeth\.A(StaticCheckOfOne|StaticCheckWhose)|^Jobs\.(ThreadsFollowTheSceneSize|CutterTipRadius|AStaticCheckOutside|PapersLattice)|^OneRegionStep\.RebuildsTheContactList|^Rating\.AHeldStaticCheck|^Cli\.GeometryDraws')
echo "test: all tests passed"
