"""Tip error of `hybeam run` CSVs against a reference CSV of the same output grid.

Usage: python3 scripts/tip_error.py REFERENCE.csv RUN.csv [RUN.csv ...]

Prints, per run, the largest Euclidean distance of the tip position from the reference over all
common rows (the 1 ms output grid of docs/accuracy.md) and the distance at the last common row.
Planar CSVs have tip.position.x, .y; spatial ones also .z.
"""

import csv
import math
import sys


def tip_history(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    head = rows[0]
    cols = [head.index(f"tip.position.{a}") for a in "xyz" if f"tip.position.{a}" in head]
    return [[float(r[c]) for c in cols] for r in rows[1:]]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    ref = tip_history(sys.argv[1])
    for path in sys.argv[2:]:
        run = tip_history(path)
        n = min(len(ref), len(run))
        dist = [math.dist(ref[i], run[i]) for i in range(n)]
        print(f"{path}: max {max(dist):.3e} m, end {dist[-1]:.3e} m ({n} rows)")


if __name__ == "__main__":
    main()
