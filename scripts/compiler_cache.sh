# Sourced by build.sh and test.sh: compile through ccache when it is there,
# with paths relative to this checkout, so that a second build of the same
# sources (another clone, the sanitizer build's next run) reuses the objects.
GEARSPH_CACHE_FLAGS=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
  GEARSPH_CACHE_FLAGS=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
