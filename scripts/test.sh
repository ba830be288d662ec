#!/usr/bin/env bash
# Installs what is missing, builds with the CI preset (-Werror, ASan, UBSan) and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset ci
cmake --build --preset ci
ctest --preset ci
