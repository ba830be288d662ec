#!/usr/bin/env python3
"""Names private to a source (its anonymous namespace) that another source of the same target
also defines. The ci and release presets compile each target in unity batches (CMakeLists.txt):
sources of a batch share one translation unit, where two such names either clash (a compile error
that appears only when a new source moves the batch boundaries) or, as overloads, let one source
call the other's function. Exits 1 naming each shared name and its sources.

Usage: check_unity_names.py ROOT  (checks ROOT/harness and ROOT/tests, the unity-built targets)
"""
import collections
import pathlib
import re
import sys

DEF = re.compile(r"^(?:(?:inline|static|constexpr|const|template <[^>]*>) )*"
                 r"[\w:<>,*& ]+?[ *&](\w+)\(")
CONST = re.compile(r"^(?:inline |static )?(?:constexpr|const) [\w:<>]+ (k\w+)\b")
TYPE = re.compile(r"^(?:struct|class|enum class|enum) (\w+)\b")


def private_names(path):
    """Top-level names of the file's anonymous namespaces (named namespaces nested in them keep
    their names apart and are skipped)."""
    names, inside, nested = set(), False, None
    for line in path.read_text(errors="replace").split("\n"):
        if nested:
            if line.startswith("}  // namespace " + nested):
                nested = None
            continue
        if line.startswith("namespace {"):
            inside = True
            continue
        if line == "}  // namespace":
            inside = False
            continue
        if not inside or line.startswith((" ", "}", "/", "#")):
            continue
        m = re.match(r"^namespace (\w+) \{", line)
        if m:
            nested = m.group(1)
            continue
        for pattern in (DEF, CONST, TYPE):
            m = pattern.match(line)
            if m and m.group(1) != "operator":
                names.add(m.group(1))
                break
    return names


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    failed = False
    for target in ("harness", "tests"):
        owners = collections.defaultdict(list)
        for source in sorted((root / target).rglob("*.cpp")):
            if "unity_names" in source.relative_to(root).parts:
                continue  # this check's own fixtures (tests/unity_names/)
            for name in private_names(source):
                owners[name].append(str(source.relative_to(root)))
        shared = {n: f for n, f in owners.items() if len(f) > 1}
        for name, files in sorted(shared.items()):
            print(f"check_unity_names: '{name}' is private to each of {', '.join(files)}")
        failed = failed or bool(shared)
        if not shared:
            print(f"check_unity_names: {len(owners)} private names, each in one source of {target}/")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
