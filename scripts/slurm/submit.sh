#!/usr/bin/env bash
# Runs a dropcheck plan on a Slurm cluster: one job-array task per shard, then a merge job that
# starts when every task has ended, however (docs/sweeps.md, "On a cluster"): when a task failed,
# timed out or was preempted, the merge lists the cells it left missing.
#
#   scripts/slurm/submit.sh --plan PLAN --shards N --out DIR --results FILE \
#                           [--dropcheck PATH] [--logs DIR] [--wait] [-- SBATCH_OPTIONS...]
#
# PLAN, DIR, FILE and the dropcheck binary must be on a file system every node sees. SBATCH_OPTIONS
# (--partition, --time, --account, --mem...) go to both jobs. Prints "array JOBID" and "merge
# JOBID"; with --wait, returns when the merge job has ended, with its exit code (0: FILE holds
# every record; 1: cells missing, listed in FILE.missing: rerun them with
# `dropcheck sweep PLAN --cells-from FILE.missing --out DIR`).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

plan="" shards="" out="" results="" logs="" wait=0
need() { [ $# -ge 2 ] || { echo "submit.sh: $1 needs a value" >&2; exit 2; }; }
dropcheck=$(command -v dropcheck || true)
while [ $# -gt 0 ]; do
  case $1 in
    --plan) need "$@"; plan=$2; shift 2 ;;
    --shards) need "$@"; shards=$2; shift 2 ;;
    --out) need "$@"; out=$2; shift 2 ;;
    --results) need "$@"; results=$2; shift 2 ;;
    --dropcheck) need "$@"; dropcheck=$2; shift 2 ;;
    --logs) need "$@"; logs=$2; shift 2 ;;
    --wait) wait=1; shift ;;
    --) shift; break ;;
    *) echo "submit.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
die() { echo "submit.sh: $*" >&2; exit 2; }
# Options after -- go to both jobs; those that would change what the jobs are are refused.
for o in "$@"; do
  case $o in
    -a|--array|--array=*|-d|--dependency|--dependency=*|-o|--output|--output=*|--wrap|--wrap=*|-W|--wait)
      die "$o after --: submit.sh sets it itself" ;;
  esac
done
[ -n "$plan" ] && [ -f "$plan" ] || die "--plan PLAN: a plan file (dropcheck plan SWEEP --out PLAN)"
[ -n "$out" ] || die "--out DIR: the folder of shard files"
[ -n "$results" ] || die "--results FILE: where the merge job writes the records"
[ -n "$dropcheck" ] && [ -x "$dropcheck" ] || die "--dropcheck PATH: the dropcheck binary"
# One task per shard, at most 1000 (a common MaxArraySize; larger plans: more cells per shard).
[[ "$shards" =~ ^[0-9]+$ ]] && [ "$shards" -ge 1 ] && [ "$shards" -le 1000 ] ||
  die "--shards N: 1 to 1000"
abs() { echo "$(cd "$(dirname -- "$1")" && pwd)/$(basename -- "$1")"; }
mkdir -p "$out" "$(dirname "$results")"
plan=$(abs "$plan") out=$(abs "$out") results=$(abs "$results") dropcheck=$(abs "$dropcheck")
logs=${logs:-$out/slurm-logs}
mkdir -p "$logs"

array=$(sbatch --parsable --array="1-$shards" --output="$logs/shard-%A_%a.out" "$@" \
  "$here/shard.sbatch" "$dropcheck" "$plan" "$shards" "$out")
array=${array%%;*}
echo "array $array"
merge_args=(--parsable --dependency="afterany:$array"
  --output="$logs/merge-%j.out" "$@")
if [ "$wait" -eq 1 ]; then
  set +e
  sbatch --wait "${merge_args[@]}" "$here/merge.sbatch" "$dropcheck" "$plan" "$out" "$results" |
    sed 's/^/merge /'
  code=${PIPESTATUS[0]}
  set -e
  exit "$code"
fi
merge=$(sbatch "${merge_args[@]}" "$here/merge.sbatch" "$dropcheck" "$plan" "$out" "$results")
echo "merge ${merge%%;*}"
