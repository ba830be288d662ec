#!/usr/bin/env python3
"""Validates result files (JSON lines of dropcheck records) against docs/results.schema.json.

    validate_records.py SCHEMA FILE...

Exit 0 when every line of every file is a valid record, 1 otherwise (each invalid line named), 77
when the jsonschema module (Debian: python3-jsonschema) is missing.
"""
import json
import sys

try:
    import jsonschema
except ImportError:
    print("validate_records: SKIPPED: no jsonschema module (Debian: python3-jsonschema)")
    sys.exit(77)


def main(argv):
    with open(argv[1], encoding="utf-8") as f:
        schema = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    bad = records = 0
    for path in argv[2:]:
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                records += 1
                errors = list(validator.iter_errors(json.loads(line)))
                for e in errors:
                    print(f"{path}:{number}: {'/'.join(map(str, e.path))}: {e.message}")
                bad += bool(errors)
    print(f"validate_records: {records - bad} of {records} records valid")
    return 1 if bad or records == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
