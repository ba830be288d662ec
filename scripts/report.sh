#!/usr/bin/env bash
# Installs what is missing, builds the release preset and writes the comparison report (reports/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset release >/dev/null
# The report needs the dropcheck binary alone, not the tests the preset also builds.
cmake --build --preset release --target dropcheck
./build/release/dropcheck report
