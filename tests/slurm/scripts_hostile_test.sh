#!/usr/bin/env bash
# ctest `scripts.slurm_hostile_input`: the Slurm helper scripts refuse hostile input (exit 2, a
# message naming the folder, file or option) before any side effect, without Slurm:
#   local_cluster.sh: a folder it did not make (a user's files are kept), a link planted in its
#     state folder, a run/shortlink naming anything but the short link folder start makes (the
#     folder named stays); and the short link folder start makes is removed by stop;
#   submit.sh: any sbatch option after -- but its allow-list, however spelled (abbreviated,
#     attached), a log path holding % # or \, a missing or bad plan or binary; nothing is created
#     and sbatch (a stand-in here) is never called; the allowed options reach sbatch rewritten.
# local_cluster.sh's refusals come before it looks for Slurm, so none of this starts a daemon.
#   scripts_hostile_test.sh DROPCHECK SOURCE_DIR
set -euo pipefail
dropcheck=$1 source=$2
cluster=$source/scripts/slurm/local_cluster.sh
submit=$source/scripts/slurm/submit.sh
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-hostile.XXXXXX")
work=$(realpath -e -- "$work")
started=()   # every folder given to `start`: stopped at the end should a refusal ever fail
cleanup() {
  local d
  for d in "${started[@]}"; do "$cluster" stop "$d" >/dev/null 2>&1 || true; done
  rm -rf -- "$work"
}
trap cleanup EXIT

checks=0 failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# refused NAME TEXT COMMAND...: COMMAND must exit 2 with TEXT on its stderr.
refused() {
  local name=$1 text=$2 rc=0
  shift 2
  checks=$((checks + 1))
  "$@" >"$work/stdout" 2>"$work/stderr" || rc=$?
  if [ "$rc" -ne 2 ]; then
    fail "$name: exit $rc, expected 2; stderr: $(head -c 400 "$work/stderr")"
  elif ! grep -qF -- "$text" "$work/stderr"; then
    fail "$name: stderr does not name '$text': $(head -c 400 "$work/stderr")"
  fi
}

# snapshot DIR: every path under DIR with its type, link target and content hash.
snapshot() {
  (cd "$1" && find . -printf '%p %y %l\n' | sort &&
    find . -type f -print0 | sort -z | xargs -0r sha256sum)
}

# kept NAME DIR BEFORE: DIR must still be exactly as BEFORE (a snapshot).
kept() {
  checks=$((checks + 1))
  [ "$(snapshot "$2")" = "$3" ] || fail "$1: $2 changed"
}

lc_start() { started+=("$1"); "$cluster" start "$1"; }
marker_text="state folder of scripts/slurm/local_cluster.sh"   # local_cluster.sh's MARKER_TEXT
# mark DIR: make DIR look like a state folder local_cluster.sh made (its marker).
mark() { mkdir -p "$1" && echo "$marker_text" >"$1/.local_cluster-state"; }

# ------------------------------------------------------------------ local_cluster.sh ----
# 1. A user's folder, holding files named like the script's own: refused, everything kept.
user=$work/user
mkdir -p "$user/log" "$user/run" "$user/munge"
echo "my notes" >"$user/notes.txt"
echo "my log" >"$user/log/mine"
echo "my run" >"$user/run/mine"
echo "my conf" >"$user/slurm.conf"
before=$(snapshot "$user")
refused "start in a user's folder" "not made by local_cluster.sh" lc_start "$user"
kept "start in a user's folder" "$user" "$before"
refused "stop in a user's folder" "not made by local_cluster.sh" "$cluster" stop "$user"
kept "stop in a user's folder" "$user" "$before"

# 2. Not a folder; a path slurm.conf cannot hold (refused before the folder is made).
echo "a file" >"$work/afile"
refused "start on a file" "not a folder" lc_start "$work/afile"
checks=$((checks + 1)); [ "$(cat "$work/afile")" = "a file" ] || fail "start on a file: changed it"
refused "start in a path with a blank" "may hold only" lc_start "$work/with blank/state"
refused "start in a path with #" "may hold only" lc_start "$work/with#hash"
checks=$((checks + 1))
if [ -e "$work/with blank" ] || [ -e "$work/with#hash" ]; then fail "a refused start made a folder"; fi

# 3. A marker that is a link, beside a user's file: not the script's marker, refused.
forged=$work/forged
mkdir -p "$forged"
echo "$marker_text" >"$work/marker-elsewhere"
ln -s "$work/marker-elsewhere" "$forged/.local_cluster-state"
echo "mine" >"$forged/notes.txt"
before=$(snapshot "$forged")
refused "start with a linked marker" "not made by local_cluster.sh" lc_start "$forged"
kept "start with a linked marker" "$forged" "$before"

# 4. Links planted in a state folder the script made: log -> victim, run -> victim.
victim=$work/victim
mkdir -p "$victim"
echo "precious" >"$victim/precious.txt"
echo "$$" >"$victim/slurmd.pid"
echo "$victim" >"$victim/shortlink"
vbefore=$(snapshot "$victim")
for entry in log run munge slurm.conf; do
  state=$work/planted-$entry
  mark "$state"
  ln -s "$victim" "$state/$entry"
  refused "start with $entry planted as a link" "symbolic link" lc_start "$state"
  refused "stop with $entry planted as a link" "symbolic link" "$cluster" stop "$state"
  kept "planted $entry" "$victim" "$vbefore"
  checks=$((checks + 1)); [ -L "$state/$entry" ] || fail "planted $entry: the link was removed"
done
state=$work/planted-pid
mark "$state"
mkdir -p "$state/run"
ln -s "$victim/slurmd.pid" "$state/run/slurmd.pid"
refused "stop with a pid file planted as a link" "symbolic link" "$cluster" stop "$state"
kept "planted pid file" "$victim" "$vbefore"

# 5. run/shortlink naming something else than the short link folder start makes (TMPDIR=$tmp).
tmp=$work/tmp
mkdir -p "$tmp/lslurm.q" "$tmp/victim" "$work/elsewhere"
echo "precious" >"$tmp/victim/precious.txt"
# shortlink_case NAME TEXT PATH: a state folder whose run/shortlink names PATH; stop and start
# refuse it naming TEXT; nothing in $tmp, $work/elsewhere or $victim changes.
shortlink_case() {
  local name=$1 text=$2 state=$work/state-$RANDOM t_before e_before
  mark "$state"
  mkdir -p "$state/run"
  echo "$3" >"$state/run/shortlink"
  t_before=$(snapshot "$tmp") e_before=$(snapshot "$work/elsewhere")
  refused "stop, shortlink $name" "$text" env TMPDIR="$tmp" "$cluster" stop "$state"
  refused "start, shortlink $name" "$text" env TMPDIR="$tmp" "$cluster" start "$state"
  started+=("$state")
  kept "shortlink $name" "$tmp" "$t_before"
  kept "shortlink $name" "$work/elsewhere" "$e_before"
  kept "shortlink $name" "$victim" "$vbefore"
}
shortlink_case ".../lslurm.q/../victim" "not named lslurm.XXXXXX" "$tmp/lslurm.q/../victim"
shortlink_case "a victim folder" "not named lslurm.XXXXXX" "$victim"
shortlink_case "lslurm.q/../lslurm.AbCdEf" "not directly in the temp folder" \
  "$tmp/lslurm.q/../lslurm.AbCdEf"
ln -s "$victim" "$tmp/lslurm.LinkEd"
shortlink_case "a link named lslurm.LinkEd" "a link" "$tmp/lslurm.LinkEd"
mkdir "$work/elsewhere/lslurm.OutSde"
shortlink_case "a folder outside the temp folder" "not directly in the temp folder" \
  "$work/elsewhere/lslurm.OutSde"
mkdir "$tmp/lslurm.NoLink"
echo "someone's" >"$tmp/lslurm.NoLink/data"
shortlink_case "a folder without the link s" "holds no link s" "$tmp/lslurm.NoLink"
mkdir "$tmp/lslurm.Stuffd"
ln -s "$work/nowhere" "$tmp/lslurm.Stuffd/s"   # s points elsewhere
shortlink_case "a folder whose s points elsewhere" "holds no link s" "$tmp/lslurm.Stuffd"

# 6. The short link folder start makes (mktemp lslurm.XXXXXX, holding only s -> the state folder)
# is removed by stop; a user's file added to the state folder stays.
state=$work/state-ours
mark "$state"
mkdir -p "$state/run"
echo "mine" >"$state/notes.txt"
short=$(TMPDIR=$tmp mktemp -d "$tmp/lslurm.XXXXXX")
ln -s "$state" "$short/s"
echo "$short" >"$state/run/shortlink"
checks=$((checks + 1))
if TMPDIR=$tmp "$cluster" stop "$state" 2>"$work/stderr"; then
  [ ! -e "$short" ] || fail "stop left its own short link folder $short"
  [ ! -e "$state/run/shortlink" ] || fail "stop left run/shortlink"
  if [ ! -f "$state/notes.txt" ] || [ ! -f "$state/.local_cluster-state" ]; then
    fail "stop removed a file it did not make"
  fi
else
  fail "stop of a state folder with its own short link failed: $(cat "$work/stderr")"
fi

# ----------------------------------------------------------------------- submit.sh ----
# A stand-in sbatch records its calls: no refusal may reach it.
mkdir -p "$work/bin"
cat >"$work/bin/sbatch" <<EOF
#!/bin/sh
printf '%s\n' "\$*" >>"$work/sbatch.calls"
echo 4242
EOF
chmod +x "$work/bin/sbatch"
export PATH="$work/bin:$PATH"
"$dropcheck" plan "$source/tests/sweeps/slurm_1000.toml" --out "$work/plan.json" >/dev/null
s=$work/s   # every refused submission writes under $s: nothing may appear there
# sub NAME TEXT ARGS...: submit.sh with a good plan, binary, shard count and folders, then ARGS
# (later options override earlier ones), must be refused naming TEXT.
sub() {
  local name=$1 text=$2
  shift 2
  refused "submit $name" "$text" "$submit" --plan "$work/plan.json" --shards 3 --out "$s/out" \
    --results "$s/results.jsonl" --dropcheck "$dropcheck" "$@"
}

# Options after --: anything but the allow-list, however sbatch would spell it.
for o in --arr=2 --array=2 "--array 2" -a2 "-a 2" --dep=afterok:1 --dependency=x "-d x" -dx \
         -ofoo "-o foo" --out=x --output=x --outp=x "-e err" --error=x --wrap=ls -W --wait \
         --chdir=/ "-D /" --export=ALL --uid=0 --part=short -vpshort "-p short --arr=2" \
         "-pshort -a2" "-t 1:00 --dep x" evil.sh; do
  read -ra words <<<"$o"
  bad=${words[-1]}
  case $o in
    "-p short --arr=2") bad=--arr=2 ;;
    "-pshort -a2") bad=-a2 ;;
    "-t 1:00 --dep x") bad=--dep ;;
    -*' '*) bad=${words[0]} ;;
  esac
  sub "-- $o" "$bad after --" -- "${words[@]}"
done
sub "-- --partition (no value)" "--partition after --: needs a value" -- --partition
sub "-- --partition=" "needs a value" -- --partition=
sub "-- -p --array=2" "-p after --: needs a value (got '--array=2')" -- -p --array=2

# Log paths Slurm would expand or cut, whether given or the current folder's.
sub "--out with %" "--out $s/sh%jards: holds '%'" --out "$s/sh%jards"
sub "--out with #" "holds '#'" --out "$s/sh#ards"
sub "--out with \\" "holds '\\'" --out "$s/sh\\ards"
sub "--out with a newline" "--out: the path holds a control character" --out "$s/sh
ards"
sub "--logs with %" "--logs $s/logs-%A: holds '%'" --logs "$s/logs-%A"
sub "--logs with #" "--logs $s/lo#gs: holds '#'" --logs "$s/lo#gs"
mkdir -p "$work/cwd%d"
(cd "$work/cwd%d" && sub "a relative --out in a folder with %" "--out $work/cwd%d/rel: holds '%'" \
  --out rel)
checks=$((checks + 1)); [ ! -e "$work/cwd%d/rel" ] || fail "a refused submission made $work/cwd%d/rel"
echo "a file" >"$work/a-file"
sub "--out a file" "--out $work/a-file: exists and is not a folder" --out "$work/a-file"
sub "--results a folder" "--results $work: is a folder" --results "$work"

# The plan and the binary.
echo '{}' >"$work/not-a-plan.json"
: >"$work/empty.json"
sub "--plan missing" "--plan $work/nope.json: no such file" --plan "$work/nope.json"
sub "--plan a folder" "--plan $work: not a file" --plan "$work"
sub "--plan {}" "--plan $work/not-a-plan.json: not a plan" --plan "$work/not-a-plan.json"
sub "--plan empty" "--plan $work/empty.json: not a plan" --plan "$work/empty.json"
sub "--plan a sweep file" "not a dropcheck plan" --plan "$source/tests/sweeps/slurm_1000.toml"
# A plan with an external engine: its tasks would need `sweep --engine-file`.
printf 'scenes = ["%s"]\nengines = ["ours", "%s"]\n' "$source/scenarios/free_fall.toml" \
  "$source/examples/python/seed_engine.toml" >"$work/external.toml"
"$dropcheck" plan "$work/external.toml" --out "$work/external.json" >/dev/null
# The same engine file edited after the plan: another fingerprint.
sed 's/^timeout = .*/timeout = 6.0/' "$source/examples/python/seed_engine.toml" >"$work/edited.toml"
sub "--plan with an external engine" "it runs an external engine" --plan "$work/external.json"
sub "--engine-file changed" "changed since \`dropcheck plan\`" --plan "$work/external.json" \
  --engine-file "$work/edited.toml"
if [ "$(id -u)" -ne 0 ]; then
  cp "$work/plan.json" "$work/unreadable.json"
  chmod 000 "$work/unreadable.json"
  sub "--plan unreadable" "--plan $work/unreadable.json: not readable" --plan "$work/unreadable.json"
else
  echo "scripts: (root reads any file: the unreadable plan case is not run)"
fi
echo "#!/bin/sh" >"$work/not-executable"
sub "--dropcheck missing" "--dropcheck $work/nobin: no such file" --dropcheck "$work/nobin"
sub "--dropcheck not executable" "--dropcheck $work/not-executable: not executable" \
  --dropcheck "$work/not-executable"
sub "--dropcheck a folder" "--dropcheck $work: not a file" --dropcheck "$work"
sub "--dropcheck true" "--dropcheck /bin/true: did not read the plan" --dropcheck /bin/true
sub "--dropcheck false" "--dropcheck /bin/false: did not read the plan" --dropcheck /bin/false
for n in 0 1001 007 abc ""; do sub "--shards '$n'" "--shards" --shards "$n"; done

checks=$((checks + 1))
[ ! -e "$s" ] || fail "refused submissions created $(find "$s" | head -n 5)"
checks=$((checks + 1))
[ ! -e "$work/sbatch.calls" ] || fail "a refused submission called sbatch: $(cat "$work/sbatch.calls")"
checks=$((checks + 1))
leftover=$(find "${TMPDIR:-/tmp}" -maxdepth 1 -name 'submit-check.*' -newer "$work/plan.json")
[ -z "$leftover" ] || fail "submit.sh left its check folder: $leftover"

# The allow-listed options reach sbatch, each rewritten as --NAME=VALUE, on both jobs.
checks=$((checks + 1))
if "$submit" --plan "$work/plan.json" --shards 3 --out "$work/ok" --results "$work/ok.jsonl" \
     --dropcheck "$dropcheck" -- -pshort --time 1:00:00 --mem=1G -c 2 --account=proj \
     -q low --constraint avx2 >"$work/stdout" 2>"$work/stderr"; then
  forwarded="--partition=short --time=1:00:00 --mem=1G --cpus-per-task=2 --account=proj"
  forwarded+=" --qos=low --constraint=avx2"
  expected="--parsable --array=1-3 --output=$work/ok/slurm-logs/shard-%A_%a.out $forwarded"
  expected+=" $source/scripts/slurm/shard.sbatch $dropcheck $work/plan.json 3 $work/ok"
  expected+=$'\n'"--parsable --dependency=afterany:4242 --output=$work/ok/slurm-logs/merge-%j.out"
  expected+=" $forwarded $source/scripts/slurm/merge.sbatch $dropcheck $work/plan.json $work/ok"
  expected+=" $work/ok.jsonl"
  [ "$(cat "$work/sbatch.calls")" = "$expected" ] ||
    fail "sbatch was called with"$'\n'"$(cat "$work/sbatch.calls")"$'\n'"expected"$'\n'"$expected"
else
  fail "a good submission was refused: $(cat "$work/stderr")"
fi

# A plan with an external engine, its engine file given: each task names it, as an absolute path.
checks=$((checks + 1))
rm -f "$work/sbatch.calls"
if (cd "$source/examples/python" && "$submit" --plan "$work/external.json" --shards 2 \
      --out "$work/ext" --results "$work/ext.jsonl" --dropcheck "$dropcheck" \
      --engine-file seed_engine.toml) >"$work/stdout" 2>"$work/stderr"; then
  grep -qF "shard.sbatch $dropcheck $work/external.json 2 $work/ext --engine-file $source/examples/python/seed_engine.toml" \
    "$work/sbatch.calls" || fail "the engine file did not reach the tasks: $(cat "$work/sbatch.calls")"
else
  fail "a submission with its engine file was refused: $(cat "$work/stderr")"
fi

if [ "$failures" -ne 0 ]; then
  echo "scripts: $failures of $checks checks failed" >&2
  exit 1
fi
echo "scripts: $checks checks passed: local_cluster.sh and submit.sh refuse hostile input" \
  "before any side effect"
