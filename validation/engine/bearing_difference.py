#!/usr/bin/env python3
"""Main-bearing loads of runs against a reference run, per channel.

usage: bearing_difference.py REF.csv RUN.csv [RUN.csv ...]

Each file is an `evas run --csv` result of the validation engine on its
crank-angle grid (one row per degree; docs/engine-bodies.md, "Modal
convergence"). Over the reference's last 720 deg, for every main-bearing
force channel (main1..5 .fx, .fy): max |F_run - F_ref| / A, with A half the
reference's peak-to-peak in that window (its amplitude about its middle).
Prints a Markdown table, one row per run and its largest channel. Rows are
matched by crank angle; a run that ended early is compared over the angles it
reached within the window, and said so. Standard library only.
"""
import csv
import sys


def read(path):
    with open(path, newline="") as f:
        rows = csv.reader(f)
        head = [h.split("[")[0].strip() for h in next(rows)]
        data = [[float(x) for x in r] for r in rows]
    return head, data


def column(head, name, path):
    if name not in head:
        sys.exit(f"{path}: no column '{name}' (columns: {', '.join(head)})")
    return head.index(name)


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    rhead, ref = read(argv[1])
    ia = column(rhead, "crank_angle", argv[1])
    names = [h for h in rhead if h.startswith("main") and h.endswith((".fx", ".fy"))]
    if not names:
        sys.exit(f"{argv[1]}: no main-bearing channels main*.fx, main*.fy")
    last = ref[-1][ia]
    window = [r for r in ref if r[ia] >= last - 720.0 - 1e-9]
    by_angle = {round(r[ia], 6): r for r in window}
    amp = {}
    for n in names:
        c = rhead.index(n)
        vals = [r[c] for r in window]
        amp[n] = 0.5 * (max(vals) - min(vals))
    print("| run | " + " | ".join(names) + " | largest |")
    print("|---|" + "---:|" * (len(names) + 1))
    for path in argv[2:]:
        head, run = read(path)
        ja = column(head, "crank_angle", path)
        matched = [(by_angle[round(r[ja], 6)], r) for r in run if round(r[ja], 6) in by_angle]
        if not matched:
            print(f"| {path} | " + " | ".join("-" for _ in names) + " | no angle of the window |")
            continue
        errs = []
        for n in names:
            c, d = rhead.index(n), column(head, n, path)
            errs.append(max(abs(b[d] - a[c]) for a, b in matched) / amp[n])
        k = max(range(len(names)), key=lambda i: errs[i])
        note = "" if len(matched) == len(window) else f" ({len(matched)} of {len(window)} angles)"
        print(f"| {path}{note} | " + " | ".join(f"{e:.2e}" for e in errs) +
              f" | {errs[k]:.2e} ({names[k]}) |")


if __name__ == "__main__":
    main(sys.argv)
