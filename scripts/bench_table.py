#!/usr/bin/env python3
"""Pairs google/benchmark's CSV of bench/loop_bench.cpp into one row per engine and body count.

usage: bench_table.py RAW.csv OUT.csv
Reads the *_median aggregates (counter ns_per_body_step) of bare/ENGINE/N, harness/ENGINE/N
and sparse/ENGINE/N; writes OUT.csv (engine, bodies, steps, bare_ns_per_body_step,
harness_ns_per_body_step, ratio = harness / bare, sparse_ns_per_body_step, sparse_ratio) and
prints the same as a Markdown table.
"""
import csv
import io
import sys


def read_medians(path):
    text = open(path, encoding="utf-8").read()
    start = text.index("name,")  # google/benchmark prints a context header before the CSV
    out = {}
    for row in csv.DictReader(io.StringIO(text[start:])):
        name = row["name"]
        if not name.endswith("_median"):
            continue
        kind, engine, rest = name.split("/", 2)
        bodies = int(rest.split("/")[0].split("_")[0])
        if row.get("error_occurred") == "true":
            sys.exit(f"bench_table.py: {name} failed: {row.get('error_message')}")
        out[(kind, engine, bodies)] = (float(row["ns_per_body_step"]), int(float(row["steps"])))
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    medians = read_medians(sys.argv[1])
    rows = []
    for (kind, engine, bodies), (ns, steps) in medians.items():
        if kind != "bare" or ("harness", engine, bodies) not in medians:
            continue
        harness = medians[("harness", engine, bodies)][0]
        sparse = medians.get(("sparse", engine, bodies), (float("nan"), 0))[0]
        rows.append((engine, bodies, steps, ns, harness, harness / ns, sparse, sparse / ns))
    if not rows:
        sys.exit("bench_table.py: no bare/harness pairs in " + sys.argv[1])
    with open(sys.argv[2], "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["engine", "bodies", "steps", "bare_ns_per_body_step",
                    "harness_ns_per_body_step", "ratio",
                    "sparse_ns_per_body_step", "sparse_ratio"])
        for r in rows:
            w.writerow([r[0], r[1], r[2], f"{r[3]:.4g}", f"{r[4]:.4g}", f"{r[5]:.3f}",
                        f"{r[6]:.4g}", f"{r[7]:.3f}"])
    print("| engine | bodies | steps | bare (ns per body-step) | harness, every step kept (ns) "
          "| harness / bare | harness, first and last kept (ns) | that / bare |")
    print("|---|--:|--:|--:|--:|--:|--:|--:|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.4g} | {r[4]:.4g} | {r[5]:.2f} | {r[6]:.4g} "
              f"| {r[7]:.2f} |")


main()
