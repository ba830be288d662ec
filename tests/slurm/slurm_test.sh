#!/usr/bin/env bash
# ctest `slurm`: a 1000-cell plan run as a Slurm job array of 7 shards on a one-node cluster started
# on localhost (scripts/slurm/local_cluster.sh: munged, slurmctld, slurmd), merged by a job that
# depends on the array, must equal a single-process run of the same plan byte for byte.
# Exit 77 (ctest: skipped) only when the Slurm packages are absent, saying so.
#   slurm_test.sh DROPCHECK SOURCE_DIR
set -euo pipefail
dropcheck=$1 source=$2
cluster=$source/scripts/slurm/local_cluster.sh
if ! missing=$("$cluster" check); then
  echo "slurm: SKIPPED: $missing" >&2
  exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-slurm.XXXXXX")
cleanup() {
  "$cluster" stop "$work/cluster" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT

"$dropcheck" plan "$source/tests/sweeps/slurm_1000.toml" --out "$work/plan.json"

start=$(date +%s%N)
"$dropcheck" sweep "$work/plan.json" --shard 1/1 --out "$work/single" --quiet
"$dropcheck" merge "$work/plan.json" "$work/single" --out "$work/single.jsonl"
single=$((($(date +%s%N) - start) / 1000000))

# Finished jobs kept 5 s: sbatch --wait then polls every 2 s instead of after 2, 8 and 32 s.
eval "$(LOCAL_SLURM_MIN_JOB_AGE=5 "$cluster" start "$work/cluster")"
start=$(date +%s%N)
"$source/scripts/slurm/submit.sh" --plan "$work/plan.json" --shards 7 --out "$work/shards" \
  --results "$work/slurm.jsonl" --dropcheck "$dropcheck" --wait
array=$((($(date +%s%N) - start) / 1000000))

shard_files=$(find "$work/shards" -maxdepth 1 -name 'shard-*.jsonl' | wc -l)
[ "$shard_files" -eq 7 ] || { echo "slurm: expected 7 shard files, found $shard_files" >&2; exit 1; }
records=$(wc -l <"$work/slurm.jsonl")
[ "$records" -eq 1000 ] || { echo "slurm: expected 1000 records, found $records" >&2; exit 1; }
if ! cmp "$work/single.jsonl" "$work/slurm.jsonl"; then
  echo "slurm: the job array's merged result differs from the single-process run" >&2
  exit 1
fi
echo "slurm: 1000 cells, 7 shards: merged result identical to one process (wall: one process" \
  "${single} ms, job array with merge ${array} ms)"
