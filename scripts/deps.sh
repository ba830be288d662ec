#!/usr/bin/env bash
# Installs what dropcheck needs from Debian 12's packages, skipping the apt calls when all are there.
# Run by scripts/report.sh and scripts/test.sh (with `test`: the tests' packages too); safe to run
# on its own.
set -euo pipefail

DROPCHECK_PACKAGES=(
  cmake g++ gcc make pkg-config        # build: the release preset (gcc: the C example engine)
  ninja-build                          # the ci preset's generator (scripts/test.sh)
  clang-14 libclang-rt-14-dev          # the ci preset's compiler and its sanitizer runtimes
  python3                              # the Python example engines and the bad-engine test doubles
  libeigen3-dev libtomlplusplus-dev    # ours, scene files
  catch2                               # tests
  libcli11-dev                         # command-line parsing (header-only CLI11)
  nlohmann-json3-dev                   # JSON output, every name escaped by construction
  libfmt-dev                           # number formatting (harness/core/number_format.hpp)
  libboost-math-dev                    # Jacobi elliptic functions (harness/oracles/free_rotation)
  gnuplot-nox                          # report plots (SVG)
  clang-format-14 git                  # scripts/format.sh and the ctest entry `format`
  libbenchmark-dev                     # benchmarks (bench/, scripts/bench.sh)
  slurmctld slurmd slurm-client munge  # sweeps on a localhost Slurm (ctest slurm, scripts/slurm/)
  python3-jsonschema                   # validates sweep records against docs/results.schema.json
  libxml2-utils                        # xmllint: validates `check --junit` (tests/check/junit.xsd)
  libcmark-gfm-dev libcmark-gfm-extensions-dev  # the report's index.html (Markdown to HTML)
)
# Only for the tests (`bash scripts/deps.sh test`, as scripts/test.sh calls it): a browser that
# opens the report's index.html (ctest report.html_browser) and its DevTools client.
if [ "${1:-}" = test ]; then
  DROPCHECK_PACKAGES+=(chromium python3-websocket)
fi
# The engines compared: the packages column of adapters/engines.txt, the one list of engines.
engines="$(dirname "${BASH_SOURCE[0]}")/../adapters/engines.txt"
while read -r name source find packages rest; do
  case "$name" in ''|'#'*) continue ;; esac
  [ "$packages" = "-" ] && continue
  IFS=, read -r -a engine_packages <<< "$packages"
  DROPCHECK_PACKAGES+=("${engine_packages[@]}")
done < "$engines"

missing=()
for p in "${DROPCHECK_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "dropcheck: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
