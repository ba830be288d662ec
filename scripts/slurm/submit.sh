#!/usr/bin/env bash
# Runs a dropcheck plan on a Slurm cluster: one job-array task per shard, then a merge job that
# starts when every task has ended, however (docs/sweeps.md, "On a cluster"): when a task failed,
# timed out or was preempted, the merge lists the cells it left missing.
#
#   scripts/slurm/submit.sh --plan PLAN --shards N --out DIR --results FILE \
#                           [--dropcheck PATH] [--logs DIR] [--engine-file FILE]... [--wait]
#                           [-- SBATCH_OPTIONS...]
#
# PLAN, DIR, FILE and the dropcheck binary must be on a file system every node sees. SBATCH_OPTIONS
# go to both jobs; only those of FORWARDED below are taken (-p short, -pshort, --partition short,
# --partition=short), anything else is refused (exit 2). Before submitting anything it checks its
# input and exits 2 naming the option and the problem: the binary must run and read PLAN as a plan
# (it is run once here, on the submitting machine), DIR and the logs folder may not hold % # or \
# (Slurm reads log paths as patterns), and a plan that names an external engine needs each given
# with --engine-file, unchanged since the plan (docs/sweeps.md, "External engines in a sweep").
# Prints "array JOBID" and "merge JOBID"; with --wait,
# returns when the merge job has ended, with its exit code (0: FILE holds every record; 1: cells
# missing, listed in FILE.missing: rerun them with
# `dropcheck sweep PLAN --cells-from FILE.missing --out DIR`).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

plan="" shards="" out="" results="" logs="" wait=0 engine_files=()
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
    --engine-file) need "$@"; engine_files+=("$2"); shift 2 ;;
    --wait) wait=1; shift ;;
    --) shift; break ;;
    *) echo "submit.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
die() { echo "submit.sh: $*" >&2; exit 2; }

# The sbatch options forwarded after --: where, when and with what resources a job runs, never
# what it runs or where its output goes (submit.sh sets --array, --output, --dependency itself).
# An allow-list, because sbatch (getopt_long) also takes any unambiguous prefix of a long option
# (--arr=2, --dep=x) and short options with their value attached (-a2, -ofile): a list of refused
# names is always bypassed. Each takes a value; the short letter, if any, follows the colon.
FORWARDED=(partition:p time:t account:A qos:q mem: mem-per-cpu: cpus-per-task:c constraint:C
  reservation: exclude:x)
forwarded_list() {   # "--partition (-p), --time (-t), ..."
  local o list=
  for o in "${FORWARDED[@]}"; do
    list+=", --${o%%:*}"
    [ -z "${o#*:}" ] || list+=" (-${o#*:})"
  done
  echo "${list#, }"
}

# The long name of forwarded option $2, given as a long name (--$2) when $1 is long, as a short
# letter (-$2) when $1 is short; fails if it is not forwarded.
forwarded_name() {
  local o
  for o in "${FORWARDED[@]}"; do
    if { [ "$1" = long ] && [ "$2" = "${o%%:*}" ]; } ||
       { [ "$1" = short ] && [ -n "${o#*:}" ] && [ "$2" = "${o#*:}" ]; }; then
      echo "${o%%:*}"; return 0
    fi
  done
  return 1
}

# Sets SBATCH_OPTS to the options after -- rewritten as --NAME=VALUE, so that sbatch reads exactly
# what was checked here; dies naming the first option that is not forwarded or lacks its value.
parse_forwarded() {
  SBATCH_OPTS=()
  local arg kind name value
  while [ $# -gt 0 ]; do
    arg=$1; shift
    case $arg in
      --?*=*) kind=long name=${arg%%=*} name=${name#--} value=${arg#*=} ;;
      --?*) kind=long name=${arg#--} value= ;;
      -?*) kind=short name=${arg:1:1} value=${arg:2} ;;      # -p VALUE or -pVALUE
      *) die "$arg after --: not an option (sbatch would run it as the batch script)" ;;
    esac
    name=$(forwarded_name "$kind" "$name") ||
      die "$arg after --: not an sbatch option submit.sh forwards; it forwards only" \
          "$(forwarded_list), long names written in full"
    if [ -z "$value" ] && [ "$arg" = "${arg%%=*}" ]; then
      [ $# -gt 0 ] || die "$arg after --: needs a value"
      value=$1; shift
    fi
    # A value that looks like an option is a forgotten value (sbatch would take it as one).
    case $value in
      ''|-*) die "$arg after --: needs a value (got '$value')" ;;
    esac
    SBATCH_OPTS+=("--$name=$value")
  done
}
parse_forwarded "$@"
# One task per shard, at most 1000 (a common MaxArraySize; larger plans: more cells per shard).
if ! [[ $shards =~ ^[1-9][0-9]{0,3}$ ]] || [ "$shards" -gt 1000 ]; then
  die "--shards ${shards:-N}: give a number of shards from 1 to 1000"
fi

# An absolute path, without resolving links (like the shell's pwd) and without creating anything.
abs() { case $1 in /*) realpath -m -s -- "$1" ;; *) realpath -m -s -- "$PWD/$1" ;; esac; }

# Slurm reads log paths (sbatch --output) as file name patterns: % starts a replacement (%j, %A,
# %a...), \ turns them off, and # cuts the name; in a folder's name any of them sends every task's
# log elsewhere or nowhere, silently. So the folders of shard files and logs may hold none of them
# (checked on the absolute path: the current folder is part of a relative one), nor a control
# character.
check_log_path() {  # OPTION PATH
  local c
  for c in % '#' "\\"; do
    case $2 in
      *"$c"*) die "$1 $2: holds '$c', which Slurm reads specially in log file names" \
                  "(%j, %A...): choose a folder whose path has no % # or \\" ;;
    esac
  done
  case $2 in *[[:cntrl:]]*) die "$1: the path holds a control character (a newline?)" ;; esac
}

[ -n "$out" ] || die "--out DIR: the folder of shard files"
[ -n "$results" ] || die "--results FILE: where the merge job writes the records"
out=$(abs "$out") results=$(abs "$results")
check_log_path --out "$out"
if [ -n "$logs" ]; then logs=$(abs "$logs"); check_log_path --logs "$logs"; fi
logs=${logs:-$out/slurm-logs}
[ ! -e "$out" ] || [ -d "$out" ] || die "--out $out: exists and is not a folder"
[ ! -e "$logs" ] || [ -d "$logs" ] || die "--logs $logs: exists and is not a folder"
[ ! -d "$results" ] || die "--results $results: is a folder; name the file to write"

# The binary: a file that can be run (found on PATH when --dropcheck is not given).
check_binary() {
  [ -n "$dropcheck" ] || die "--dropcheck PATH: no dropcheck on PATH; name the binary"
  [ -e "$dropcheck" ] || die "--dropcheck $dropcheck: no such file"
  [ -f "$dropcheck" ] || die "--dropcheck $dropcheck: not a file"
  [ -x "$dropcheck" ] || die "--dropcheck $dropcheck: not executable"
}

# The plan: a readable file that this binary reads as a plan. Merging it with no shard file reads
# and checks the whole plan and lists every cell as missing (exit 1, the list not empty); a file
# that is not a plan, or one this binary cannot read, exits 2 with dropcheck's reason. Runs in a
# temporary folder of its own, removed after, with no input and at most 5 minutes.
check_plan() {
  [ -n "$plan" ] || die "--plan PLAN: the plan file (dropcheck plan SWEEP --out PLAN)"
  [ -e "$plan" ] || die "--plan $plan: no such file"
  [ -f "$plan" ] || die "--plan $plan: not a file"
  [ -r "$plan" ] || die "--plan $plan: not readable"
  local rc=0 said
  checkdir=$(mktemp -d "${TMPDIR:-/tmp}/submit-check.XXXXXX")
  mkdir "$checkdir/shards"
  said=$(timeout 300 "$dropcheck" merge "$plan" "$checkdir/shards" --out "$checkdir/results" \
         --missing "$checkdir/missing" 2>&1 </dev/null) || rc=$?
  if [ "$rc" -eq 2 ]; then
    die "--plan $plan: not a plan $dropcheck can run: ${said##*$'\n'}"
  elif [ "$rc" -ne 1 ] || [ ! -s "$checkdir/missing" ]; then
    die "--dropcheck $dropcheck: did not read the plan as dropcheck does (dropcheck merge exited" \
        "$rc${said:+: ${said##*$'\n'}})"
  fi
  # An external engine's cells (engine NAME@FINGERPRINT) run only with `sweep --engine-file`: each
  # must be given, unchanged since the plan, or every task would fail. `sweep` checks them before
  # it reads its list of cells, so an empty list passes that check and stops there ("lists no
  # cell"), running nothing.
  if grep -q '^[^|]*|[^|]*@' "$checkdir/missing"; then
    [ ${#engine_files[@]} -gt 0 ] ||
      die "--plan $plan: it runs an external engine (an engine file or exec:); give each with" \
          "--engine-file FILE, on a file system every node sees"
    : >"$checkdir/none"
    said=$(timeout 300 "$dropcheck" sweep "$plan" --cells-from "$checkdir/none" \
           --out "$checkdir/dry" "${engine_args[@]}" 2>&1 </dev/null) || true
    case $said in
      *"lists no cell"*) ;;
      *) die "--engine-file: ${said##*$'\n'}" ;;
    esac
  fi
  rm -rf -- "$checkdir"; checkdir=
}
checkdir=
trap '[ -z "$checkdir" ] || rm -rf -- "$checkdir"' EXIT
# Each engine file as an absolute path (exec:PATH too), as every task will name it.
engine_args=()
for f in ${engine_files[@]+"${engine_files[@]}"}; do
  case $f in
    exec:*) engine_args+=(--engine-file "exec:$(abs "${f#exec:}")") ;;
    *) engine_args+=(--engine-file "$(abs "$f")") ;;
  esac
done
check_binary
check_plan
plan=$(abs "$plan") dropcheck=$(abs "$dropcheck")

mkdir -p "$out" "$(dirname "$results")" "$logs"

array=$(sbatch --parsable --array="1-$shards" --output="$logs/shard-%A_%a.out" "${SBATCH_OPTS[@]}" \
  "$here/shard.sbatch" "$dropcheck" "$plan" "$shards" "$out" ${engine_args[@]+"${engine_args[@]}"})
array=${array%%;*}
echo "array $array"
merge_args=(--parsable --dependency="afterany:$array"
  --output="$logs/merge-%j.out" "${SBATCH_OPTS[@]}")
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
