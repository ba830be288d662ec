#!/usr/bin/env bash
# ctest check.friction_suite: `dropcheck check scenarios/friction` (the ramp grid, the stopping
# distances, the bounce phases; docs/contact.md) on every engine of the build. Every engine that
# collides runs every scene (a skip is only "no contacts"), and the failures and limits are exactly
# those of tests/check/friction_known_failures.txt, each naming its cause.
#   friction_suite.sh DROPCHECK SOURCE_DIR PYTHON
set -euo pipefail
dropcheck=$1 source=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-friction.XXXXXX")
trap 'rm -rf "$work"' EXIT
code=0
"$dropcheck" check "$source/scenarios/friction" --json "$work/suite.json" > "$work/suite.txt" || code=$?
[ "$code" -le 1 ] || { echo "friction_suite: check exited $code"; tail "$work/suite.txt"; exit 1; }
exec "$python" - "$work/suite.json" "$source/tests/check/friction_known_failures.txt" <<'PY'
import json, sys


def check(ok, why):
    """An explicit check (an assert would vanish under python -O)."""
    if not ok:
        sys.exit("friction_suite: " + why)


results = json.load(open(sys.argv[1], encoding="utf-8"))["results"]
known = {}
for line in open(sys.argv[2], encoding="utf-8"):
    if line.strip() and not line.startswith("#"):
        verdict, scene, engine, cause = line.split(maxsplit=3)
        known[(verdict, scene, engine)] = cause.strip()
scenes = {r["scene"] for r in results}
check(len(scenes) == 44, f"{len(scenes)} scenes, expected 25 ramps + 3 stops + 16 bounce phases")
colliders = {r["engine"] for r in results if r["verdict"] != "skipped"}
bad = [r for r in results if r["verdict"] == "skipped" and r["message"] != "no contacts"]
check(not bad, f"a colliding engine skipped a scene: {bad[:3]}")
for e in sorted(colliders):
    ran = {r["scene"] for r in results if r["engine"] == e and r["verdict"] != "skipped"}
    check(ran == scenes, f"{e} did not run {sorted(scenes - ran)}")
failed = {(r["verdict"], r["scene"], r["engine"]): r["message"] + " " + r["limit"]
          for r in results if r["verdict"] in ("fail", "limit")}
known = {k: c for k, c in known.items() if k[2] in colliders}  # engines this build has
check(set(failed) == set(known),
      f"failures and limits {sorted(failed)} are not the known {sorted(known)}: a new one, or a "
      "fixed one to take out of tests/check/friction_known_failures.txt")
for key, cause in known.items():
    check(cause in failed[key], f"{key}: the verdict does not name '{cause}': {failed[key]}")
passed = sum(r["verdict"] == "pass" for r in results)
print(f"friction_suite: {len(scenes)} scenes on {len(colliders)} colliding engines "
      f"({', '.join(sorted(colliders))}): {passed} checks passed, {len(failed)} known failures and limits named")
PY
