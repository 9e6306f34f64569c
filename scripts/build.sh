#!/usr/bin/env bash
# Build the catkin workspace (after `make setup` installed the dependencies); arguments are
# catkin_make's (targets, -j…). scripts/setup.sh runs `build.sh all tests`: the gtest
# executables (catkin_add_gtest targets named gtest_*) are built with the rest and
# scripts/run_tests.py runs them. ccache keeps C++ rebuilds of a fresh clone fast.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
cd "$REPO/catkin_ws"
mkdir -p "$REPO/.deps"
exec 9>"$REPO/.deps/build.lock"; flock 9     # one catkin_make at a time in this workspace
launcher=()
# ccache keyed on paths relative to the repository: a fresh clone elsewhere hits the cache
export CCACHE_BASEDIR="$REPO" CCACHE_NOHASHDIR=1
if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@"
