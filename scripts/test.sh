#!/usr/bin/env bash
# Installs what is missing, builds with the CI preset (-Werror, ASan, UBSan) and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh test
# The ci preset builds with Ninja (it compiles the tests while the libraries are still building,
# where make waits for each library): a build/ci that make configured is started afresh, since
# CMake cannot switch a build folder's generator.
if [ -f build/ci/CMakeCache.txt ] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=Ninja' build/ci/CMakeCache.txt; then
  echo "test.sh: build/ci was configured for another generator; removing it" >&2
  rm -rf build/ci
fi
cmake --preset ci
cmake --build --preset ci
ctest --preset ci
