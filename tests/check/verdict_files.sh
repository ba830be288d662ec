#!/usr/bin/env bash
# ctest check.verdict_files: `dropcheck check --junit --json` on a passing, a failing (the example
# engine with its damping in the wrong place) and a skipping engine; the JUnit file validated
# against tests/check/junit.xsd by Debian's xmllint, the JSON against docs/check.schema.json by
# python3-jsonschema; both count what the printed lines count; a second run writes the same bytes.
#   verdict_files.sh DROPCHECK SOURCE_DIR PYTHON
set -euo pipefail
dropcheck=$1 source=$2 python=$3
command -v xmllint >/dev/null || { echo "verdict_files: SKIPPED: no xmllint (Debian: libxml2-utils)"; exit 77; }
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-verdicts.XXXXXX")
trap 'rm -rf "$work"' EXIT
run() {
  set +e
  "$dropcheck" check "$source/scenarios/throw_up.toml" "$source/scenarios/throw_3d.toml" \
    --engine ours --engine box2d --engine "$source/examples/python/wrong_order.toml" \
    --junit "$work/$1.xml" --json "$work/$1.json" > "$work/$1.txt"
  echo $? > "$work/$1.code"
  set -e
}
run first
run second
[ "$(cat "$work/first.code")" = 1 ] || { echo "expected exit 1 (a check failed)"; exit 1; }
cmp "$work/first.xml" "$work/second.xml"
cmp "$work/first.json" "$work/second.json"
xmllint --noout --schema "$source/tests/check/junit.xsd" "$work/first.xml"
exec "$python" - "$source/docs/check.schema.json" "$work/first.json" "$work/first.xml" \
  "$work/first.txt" <<'PY'
import json, sys, xml.etree.ElementTree as ET
try:
    import jsonschema
except ImportError:
    print("verdict_files: SKIPPED: no jsonschema module (Debian: python3-jsonschema)")
    sys.exit(77)
schema, doc = (json.load(open(p, encoding="utf-8")) for p in sys.argv[1:3])
jsonschema.Draft202012Validator.check_schema(schema)
jsonschema.Draft202012Validator(schema).validate(doc)
lines = open(sys.argv[4], encoding="utf-8").read().splitlines()
printed = {"pass": sum(l.startswith("PASS ") for l in lines),
           "limit": sum(l.startswith("LIMIT ") for l in lines),
           "fail": sum(l.startswith("FAIL ") for l in lines),
           "skipped": sum(l.startswith("skipped: ") for l in lines)}
counted = {"pass": doc["passed"], "limit": doc["limits"], "fail": doc["failed"],
           "skipped": doc["skipped"]}
assert printed == counted, (printed, counted)
assert printed["fail"] > 0 and printed["pass"] > 0 and printed["skipped"] > 0, printed
root = ET.parse(sys.argv[3]).getroot()
assert int(root.get("tests")) == sum(printed.values()), root.attrib
assert int(root.get("failures")) == printed["fail"] and int(root.get("skipped")) == printed["skipped"]
failures = root.findall(".//failure")
assert all(f.get("message") for f in failures), "a failure without its verdict"
print(f"verdict_files: {len(doc['results'])} results, JUnit and JSON valid and agreeing: {printed}")
PY
