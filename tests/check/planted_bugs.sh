#!/usr/bin/env bash
# ctest check.planted_bugs: an engine author's engine (tests/check/author_engine.py, written from
# docs/protocol.md) with three planted contact bugs, driven as its author would drive it. Without a
# bug it passes `check` and is blessed. With each bug, `check` names the first departing step and
# the cause, `bless --check` fails its physics tier with the same words, `bless` refuses and writes
# nothing, and `diff` says what moved in contact terms.
#   planted_bugs.sh DROPCHECK SOURCE_DIR PYTHON
set -euo pipefail
dropcheck=$1 source=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-planted.XXXXXX")
trap 'rm -rf "$work"' EXIT
for mode in correct friction_after_position grip_whole_gravity restitution_twice; do
  printf 'name = "author"\ncommand = ["%s", "%s", "%s"]\ntimeout = 30.0\n' \
    "$python" "$source/tests/check/author_engine.py" "$mode" > "$work/$mode.toml"
done
scenes=()
for s in slide_stop incline_slide incline_hold bounce_e05 drop_on_floor; do
  scenes+=("$source/scenarios/$s.toml")
done

# run NAME EXPECTED_EXIT COMMAND...: its output in $work/NAME.txt, its exit code checked.
run() {
  local name=$1 expected=$2 code=0
  shift 2
  "$@" > "$work/$name.txt" 2>&1 || code=$?
  [ "$code" = "$expected" ] || { echo "$name: exit $code, expected $expected"; cat "$work/$name.txt"; exit 1; }
}
# says NAME LINE_START TEXT...: the line of $work/NAME.txt starting LINE_START holds every TEXT.
says() {
  local name=$1 start=$2 line
  shift 2
  line=$(grep -F -- "$start" "$work/$name.txt" | head -1) || true
  [ -n "$line" ] || { echo "$name: no line starting '$start':"; cat "$work/$name.txt"; exit 1; }
  for text in "$@"; do
    case "$line" in
      *"$text"*) ;;
      *) echo "$name: no '$text' in the line starting '$start':"; cat "$work/$name.txt"; exit 1 ;;
    esac
  done
}

run check.correct 0 "$dropcheck" check "${scenes[@]}" --engine "$work/correct.toml"
says check.correct "author alone:" "5 passed, 0 failed"
run bless.correct 0 "$dropcheck" bless "${scenes[@]}" --engine "$work/correct.toml" --out "$work/base"
run recheck.correct 0 "$dropcheck" bless --check "${scenes[@]}" --engine "$work/correct.toml" \
  --baselines "$work/base"

# bug MODE SCENE STEP CAUSE: one planted bug, caught by check on every scene, and on SCENE at STEP
# with CAUSE by check, bless --check and bless (these two on SCENE alone, to keep the test short).
bug() {
  local mode=$1 scene=$2 departs=$3 cause=$4
  run "check.$mode" 1 "$dropcheck" check "${scenes[@]}" --engine "$work/$mode.toml"
  says "check.$mode" "FAIL  $scene  author" "$departs" "$cause"
  run "recheck.$mode" 1 "$dropcheck" bless --check "$source/scenarios/$scene.toml" \
    --engine "$work/$mode.toml" --baselines "$work/base" --tier physics
  says "recheck.$mode" "FAILED: $scene / author / physics: contact:" "$departs" "$cause"
  # `bless` into a project's tests/baselines refuses, naming the same, and writes nothing.
  mkdir -p "$work/project.$mode/tests/baselines"
  (cd "$work/project.$mode" &&
    run "bless.$mode" 1 "$dropcheck" bless "$source/scenarios/$scene.toml" --engine "$work/$mode.toml")
  says "bless.$mode" "dropcheck bless: refused: $scene / author / physics" "$departs" "$cause"
  [ -z "$(ls -A "$work/project.$mode/tests/baselines")" ] || { echo "bless.$mode wrote a baseline"; exit 1; }
}
bug friction_after_position slide_stop "DEPARTS at step 1 " \
  "it follows its law with the friction resolved after the position update"
says check.friction_after_position "FAIL  bounce_e05  author" "DEPARTS at step 28 " \
  "it follows its law with the contact resolved after the position update"
says check.friction_after_position "FAIL  drop_on_floor  author" \
  "first departs at step 116 (rest height)" "its contact is resolved after the position update"
bug grip_whole_gravity incline_slide "DEPARTS at step 1 " "the normal force ignores the incline"
says check.grip_whole_gravity "FAIL  incline_hold  author" "the normal force ignores the incline"
says check.grip_whole_gravity "PASS  slide_stop  author"
bug restitution_twice bounce_e05 "DEPARTS at step 28 " "it follows its law with the restitution applied twice"

# `diff` names what moved in contact terms (`bless --out` elsewhere writes a failing run, marked).
moved() {
  local mode=$1
  shift
  run "out.$mode" 1 "$dropcheck" bless "$@" --engine "$work/$mode.toml" --out "$work/$mode"
  run "diff.$mode" 0 "$dropcheck" diff "$work/base" "$work/$mode"
}
moved grip_whole_gravity "$source/scenarios/incline_slide.toml" "$source/scenarios/incline_hold.toml"
moved restitution_twice "$source/scenarios/bounce_e05.toml"
says diff.grip_whole_gravity "| incline_slide | author | cube.stop_step |" "slides on -> never moves"
says diff.grip_whole_gravity "| incline_hold | author | launched.stop_step |" "120 -> 97"
says diff.restitution_twice "| bounce_e05 | author | ball.apex_1 |" "0.2667778 m -> 1.029"
echo "planted_bugs: three planted bugs each caught by check, bless --check and bless, with step and cause"
