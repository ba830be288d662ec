#!/usr/bin/env python3
"""The folder order of docs/design.md, kept: every #include of a dropcheck header must point down.

docs/design.md states the order in its "Layout" section, one line per rule:

    layers: cli > plan > ... > core        harness/ folders, top first; each includes only itself
                                            and the folders after it
    uses: adapters -> core, io, ...        a folder outside harness/ and the harness folders it
                                            may include ("nothing" for none)

Exit 0 when every include follows the order, 1 listing each one that does not (file, line, the
folder it reaches), 2 when the order itself cannot be read. Usage: check_layers.py [ROOT].
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"(harness|adapters|ours)/([A-Za-z0-9_]+/)?')


def read_order(design):
    layers, uses = None, {}
    for line in design.read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if line.startswith("layers:"):
            layers = [f.strip() for f in line[len("layers:"):].split(">")]
        elif line.startswith("uses:"):
            user, _, allowed = line[len("uses:"):].partition("->")
            allowed = allowed.strip()
            uses[user.strip()] = [] if allowed == "nothing" else [a.strip() for a in allowed.split(",")]
    if not layers:
        sys.exit(f"check_layers: {design}: no 'layers:' line in the Layout section")
    return layers, uses


def target_of(match):
    top, sub = match.group(1), match.group(2)
    return sub.rstrip("/") if top == "harness" and sub else top


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    layers, uses = read_order(root / "docs/design.md")
    rank = {folder: i for i, folder in enumerate(layers)}
    problems, files = [], 0
    sources = [p for p in root.glob("harness/*/*") if p.suffix in (".hpp", ".cpp")]
    for user in uses:
        sources += [p for p in (root / user).rglob("*") if p.suffix in (".hpp", ".cpp", ".h", ".c")]
    for path in sorted(sources):
        files += 1
        rel = path.relative_to(root)
        folder = rel.parts[1] if rel.parts[0] == "harness" else rel.parts[0]
        if rel.parts[0] == "harness" and folder not in rank:
            problems.append(f"{rel}: folder harness/{folder}/ is not in the order of docs/design.md")
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = target_of(match)
            if target == folder:
                continue
            if rel.parts[0] == "harness":
                ok = target in rank and rank[target] > rank[folder]
                rule = f"harness/{folder}/ may include only the folders below it"
            else:
                ok = target in uses[folder]
                rule = f"{folder}/ may include only {', '.join(uses[folder]) or 'nothing of dropcheck'}"
            if not ok:
                problems.append(f"{rel}:{number}: includes {target}/ ({rule})")
    for problem in problems:
        print(problem)
    print(f"check_layers: {files} files, {len(problems)} includes against the order "
          f"{' > '.join(layers)}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
