#!/usr/bin/env bash
# ctest results.schema: the shipped example (docs/results-example.jsonl) and the records this build
# writes for tests/sweeps/example.toml, validated against docs/results.schema.json.
#   fresh_records.sh DROPCHECK SOURCE_DIR PYTHON
set -euo pipefail
dropcheck=$1 source=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/dropcheck-records.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$dropcheck" plan "$source/tests/sweeps/example.toml" --out "$work/plan.json"
"$dropcheck" sweep "$work/plan.json" --shard 1/1 --out "$work/shards" --quiet
"$dropcheck" merge "$work/plan.json" "$work/shards" --out "$work/results.jsonl"
exec "$python" "$source/tests/results/validate_records.py" "$source/docs/results.schema.json" \
  "$source/docs/results-example.jsonl" "$work/results.jsonl"
