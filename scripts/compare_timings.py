#!/usr/bin/env python3
"""Compares the wall-clock timings of two `dropcheck report` folders.

    python3 scripts/compare_timings.py REPORT_A REPORT_B [--tolerance 0.10] [--worst 10]
                                       [--min-share S]

Reads REPORT_A/README.md and REPORT_B/README.md, takes every "⏱ median (ms per sim s)" cell of the
"Error against run time" tables (one cell per scene, engine and step h), and prints how many of the
cells present in both agree within the tolerance (max/min - 1 <= tolerance; 0.10 = 10 %), the share
per engine, and the cells that moved most. Two reports of the same build on the same quiet
machine should agree on at least 95 % of the cells within 10 %.

Exit status: 0; 1 when --min-share is given and the share is below it; 2 on bad input (a missing
file, or a report without timings).
"""
import argparse
import os
import sys

MEDIAN_COLUMN = "⏱ median (ms per sim s)"


def fail(message):
    print(f"compare_timings: {message}", file=sys.stderr)
    sys.exit(2)


def cells(line):
    """The cells of one Markdown table row, stripped."""
    return [c.strip() for c in line.strip().strip("|").split("|")]


def read_medians(folder):
    """{(scene, engine, h): median ms per sim s} from a report folder's README.md."""
    path = os.path.join(folder, "README.md")
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail(f"{path}: cannot read ({e.strerror})")
    medians, scene, header = {}, None, None
    for line in lines:
        if line.startswith("### "):
            scene, header = line[4:].strip(), None
        elif not line.startswith("|"):
            header = None
        elif header is None:
            header = cells(line)
        elif not set(line) <= set("|-: "):  # a data row, not the alignment row
            if MEDIAN_COLUMN not in header or scene is None:
                continue
            row = dict(zip(header, cells(line)))
            try:
                value = float(row[MEDIAN_COLUMN])
            except (KeyError, ValueError):
                continue  # an engine that did not run at this step: no figure
            medians[(scene, row.get("engine", "?"), row.get("h", "?"))] = value
    if not medians:
        fail(f"{path}: no '{MEDIAN_COLUMN}' cells (a report made with --no-timing?)")
    return medians


def stated_spread(folder):
    """The report's own 'Timing reproducibility' sentence, or None."""
    with open(os.path.join(folder, "README.md"), encoding="utf-8") as f:
        text = f.read()
    at = text.find("## Timing reproducibility")
    if at < 0:
        return None
    body = text[at:].split("\n\n", 2)
    return body[1].strip() if len(body) > 1 else None


def ratio(a, b):
    """max/min - 1: how far two positive figures differ (0.1 = 10 %); inf if one is 0."""
    lo, hi = min(a, b), max(a, b)
    return hi / lo - 1 if lo > 0 else float("inf")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("report_a")
    p.add_argument("report_b")
    p.add_argument("--tolerance", type=float, default=0.10, help="relative, default 0.10")
    p.add_argument("--worst", type=int, default=10, help="cells listed, default 10")
    p.add_argument("--min-share", type=float, help="exit 1 when the agreeing share is below")
    args = p.parse_args()
    if not args.tolerance >= 0:
        fail("--tolerance must be >= 0")
    a, b = read_medians(args.report_a), read_medians(args.report_b)
    common = sorted(set(a) & set(b))
    if not common:
        fail("the two reports share no timing cell (different scenes or engines?)")
    moved = sorted(((ratio(a[k], b[k]), k) for k in common), reverse=True)
    agree = sum(1 for r, _ in moved if r <= args.tolerance)
    share = agree / len(common)
    tol = f"{100 * args.tolerance:g} %"
    print(f"{agree} of {len(common)} median timings agree within {tol}: {100 * share:.1f} %")
    only = len(set(a) ^ set(b))
    if only:
        print(f"({only} cells are in only one of the two reports and are not compared)")
    per_engine = {}
    for r, (_, engine, _) in moved:
        n, ok = per_engine.get(engine, (0, 0))
        per_engine[engine] = (n + 1, ok + (r <= args.tolerance))
    print("\nper engine: " + ", ".join(f"{e} {ok}/{n}" for e, (n, ok) in sorted(per_engine.items())))
    print(f"\nmoved most ({args.report_a} -> {args.report_b}, ms per sim s):")
    print("| scene | engine | h | A | B | max/min - 1 |")
    print("|---|---|---|--:|--:|--:|")
    for r, k in moved[: max(args.worst, 0)]:
        print(f"| {k[0]} | {k[1]} | {k[2]} | {a[k]:.3g} | {b[k]:.3g} | {100 * r:.1f} % |")
    for folder in (args.report_a, args.report_b):
        s = stated_spread(folder)
        if s:
            print(f"\n{folder} states: {s}")
    if args.min_share is not None and share < args.min_share:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
