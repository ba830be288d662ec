#!/usr/bin/env bash
# Benchmarks the harness loop (run_scene) against each engine's bare stepping loop (bench/): builds
# the release preset with -DDROPCHECK_BUILD_BENCH=ON, runs build/release/bench/dropcheck_bench (3
# repetitions, medians), writes bench/results/MACHINE.csv and prints it as a Markdown table.
#   bash scripts/bench.sh [MACHINE]     MACHINE defaults to the short host name
#   DROPCHECK_BENCH_NO_BUILD=1 ...      use the binary already built
# Run it on a quiet machine: anything else running moves the figures.
set -euo pipefail
cd "$(dirname "$0")/.."
machine=${1:-$(hostname -s)}
if [ "${DROPCHECK_BENCH_NO_BUILD:-0}" != 1 ]; then
  bash scripts/deps.sh
  cmake --preset release -DDROPCHECK_BUILD_BENCH=ON >/dev/null
  cmake --build --preset release --target dropcheck_bench
fi
mkdir -p bench/results
raw=$(mktemp)
trap 'rm -f "$raw"' EXIT
# The loop benchmarks only (bare/harness/sparse): google benchmark's CSV needs the same counters in
# every row, and the protocol benchmarks (bench/exec_bench.cpp, BM_*Step) have none; run those with
# ./build/release/bench/dropcheck_bench --benchmark_filter=Step
./build/release/bench/dropcheck_bench --benchmark_filter='^(bare|harness|sparse)/' \
  --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true --benchmark_min_time=0.2 \
  --benchmark_out="$raw" --benchmark_out_format=csv >&2
python3 scripts/bench_table.py "$raw" "bench/results/$machine.csv"
