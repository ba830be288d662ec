#!/usr/bin/env bash
# Installs what is missing, builds the release preset and writes the comparison report (reports/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
./build/release/dropcheck report
