#!/usr/bin/env bash
# ctest sweep.killed_shard: a shard killed mid-run (SIGTERM, then SIGKILL) leaves no shard file,
# and a shard file from an earlier complete run of the same shard stays as it was.
#   killed_shard.sh DROPCHECK SOURCE_DIR
set -euo pipefail
dropcheck=$1 source=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-killed.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$dropcheck" plan "$source/sweeps/small.toml" --out "$work/plan.json" >/dev/null

# Starts the shard in the background and returns once a few of its cells are done (the progress
# lines say so), long before the last one; its pid in $pid.
start_shard() {
  "$dropcheck" sweep "$work/plan.json" --shard 1/1 --out "$work/out" 2>"$work/progress" &
  pid=$!
  for _ in $(seq 1 200); do
    [ "$(grep -c '^cell ' "$work/progress" || true)" -ge 5 ] && return
    sleep 0.05
  done
}

for signal in TERM KILL; do
  rm -rf "$work/out"
  start_shard
  kill -"$signal" "$pid"
  wait "$pid" && { echo "killed_shard: the sweep was not killed (SIG$signal)" >&2; exit 1; }
  left=$(find "$work/out" -mindepth 1 2>/dev/null | wc -l)
  [ "$left" -eq 0 ] || { echo "killed_shard: SIG$signal left files:" >&2; ls -la "$work/out" >&2; exit 1; }
done
# A complete run, then a rerun killed: the complete file survives unchanged.
"$dropcheck" sweep "$work/plan.json" --shard 1/1 --out "$work/out" --quiet >/dev/null
cp "$work/out/shard-1-of-1.jsonl" "$work/complete"
start_shard
kill -KILL "$pid"
wait "$pid" || true
cmp "$work/complete" "$work/out/shard-1-of-1.jsonl"
[ "$(find "$work/out" -mindepth 1 | wc -l)" -eq 1 ] || { ls -la "$work/out" >&2; exit 1; }
echo "killed_shard: SIGTERM and SIGKILL mid-run left nothing; a killed rerun left the complete file"
