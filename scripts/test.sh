#!/usr/bin/env bash
# Installs what is missing, builds with the CI preset (-Werror, ASan, UBSan) and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh test
# The ci preset builds with Ninja (it compiles the tests while the libraries are still building,
# where make waits for each library) and Clang 14 (its sanitized builds take half GCC 12's CPU
# time): a build/ci configured with another generator or compiler is started afresh, since CMake
# cannot switch a build folder's generator or compiler.
cache=build/ci/CMakeCache.txt
if [ -f $cache ] && ! { grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' $cache &&
                        grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++-14$' $cache; }; then
  echo "test.sh: build/ci was configured for another generator or compiler; removing it" >&2
  rm -rf build/ci
fi
cmake --preset ci
cmake --build --preset ci
ctest --preset ci
