#!/usr/bin/env bash
# Fuzzes what reads a stranger's bytes with libFuzzer (clang, AddressSanitizer and
# UndefinedBehaviorSanitizer), one target after the other: the scene loader, the baseline parser,
# the timings record reader, the trajectory CSV reader of `identify --trajectory`, and the engine
# protocol reader (what an external engine answers), and the sweep plan reader with the cell set-up
# it feeds.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]   SECONDS per target (default 600); TARGET scene_loader,
#                                           baseline_parse, timing_record, trajectory_csv,
#                                           exec_protocol, plan_reader (default all six)
#   scripts/fuzz.sh --build-only            only compile build/fuzz/<target>
#
# Seeds: scenarios/ (scenes), tests/baselines/ (baselines) and reports/ (timings.json), plus
# fuzz/regressions/<target>/ (seed transcripts and CSVs, and inputs that once found a bug). New corpus entries go to build/fuzz/corpus/<target>/, crashes to
# build/fuzz/findings/<target>/ (libFuzzer prints the input's path and the reproducer command).
# Exit status: 0 when every target ran its time without a finding, 1 otherwise.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=$root/build/fuzz
cxx=${CXX_FUZZ:-clang++}
build_only=0
seconds=600
targets=()
for a in "$@"; do
  case $a in
    --build-only) build_only=1 ;;
    ''|*[!0-9]*) targets+=("$a") ;;
    *) seconds=$a ;;
  esac
done
[ ${#targets[@]} -gt 0 ] || targets=(scene_loader baseline_parse timing_record trajectory_csv exec_protocol
  plan_reader)

# The sources a target needs (a static library: only what is referenced gets linked). toml++ is
# compiled header-only here so that its parser is instrumented too, with its internal debug
# assertions off as in the library dropcheck links (the loader refuses control characters before
# toml++ sees them, and hands it ASCII only: harness/scene/toml_ascii.hpp).
sources=("$root"/harness/{core,scene,io,process}/*.cpp "$root"/harness/guard/baseline_parse.cpp "$root"/harness/guard/baseline_io.cpp
         "$root"/harness/report/timing_record.cpp "$root"/adapters/exec_protocol.cpp
         "$root"/harness/plan/{plan,axes,sweep_file}.cpp)
flags=(-std=c++20 -O1 -g -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
       -fno-sanitize-recover=all -ffp-contract=off -I"$root" -I/usr/include/eigen3
       -DTOML_HEADER_ONLY=1 '-DTOML_ASSERT(expr)=static_assert(true)')

build() {
  mkdir -p "$out/obj"
  local objs=()
  for src in "${sources[@]}"; do
    local obj=$out/obj/$(basename "${src%.cpp}").o
    if [ ! -f "$obj" ] || [ "$src" -nt "$obj" ]; then "$cxx" "${flags[@]}" -c "$src" -o "$obj"; fi
    objs+=("$obj")
  done
  rm -f "$out/libharness.a"
  ar rcs "$out/libharness.a" "${objs[@]}"
  for t in "${targets[@]}"; do
    "$cxx" "${flags[@]}" -fsanitize=fuzzer "$root/fuzz/${t}_fuzz.cpp" "$out/libharness.a" -lfmt -o "$out/$t"
  done
}

seeds() {
  case $1 in
    scene_loader) echo "$root/scenarios" ;;
    baseline_parse) echo "$root/tests/baselines" ;;
    timing_record) echo "$root/reports" ;;
    trajectory_csv|exec_protocol|plan_reader) echo "$root/fuzz/regressions/$1" ;;
  esac
}

# One build at a time on this machine: the same lock as the project's build wrapper (dcbuild).
( flock 9; build ) 9>/tmp/dropcheck-build.lock
[ $build_only = 1 ] && exit 0
status=0
for t in "${targets[@]}"; do
  mkdir -p "$out/corpus/$t" "$out/findings/$t"
  echo "fuzz: $t for ${seconds} s"
  # -rss_limit_mb: a leak or runaway allocation is a finding; -timeout: a slow input is one too.
  if ! "$out/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -artifact_prefix="$out/findings/$t/" -print_final_stats=1 \
        "$out/corpus/$t" "$(seeds "$t")" "$root/fuzz/regressions/$t"; then
    status=1
  fi
done
exit $status
