#!/usr/bin/env python3
"""Difference of a periodic cycle (evas periodic) from a transient run's last
whole cycle, channel by channel, on the crank-angle grid.

usage: periodic_compare.py PERIODIC.csv TRANSIENT.csv [PATTERN ...]

Each file is an `evas periodic --csv` or `evas run --csv` result (or `evas
export RESULTS.h5 --csv FILE`). Rows are matched by crank angle modulo
720 deg, the transient's over its last 720 deg. Per channel: max over the
cycle of |periodic - transient| / max over the cycle of |transient| (the
measure of the tables in docs/periodic.md); per pattern (shell-style; default
main*.fx main*.fy mount*.f*) the worst channel. Standard library only.
"""
import csv
import fnmatch
import sys


def read(path):
    with open(path, newline="") as f:
        rows = csv.reader(f)
        head = [h.split("[")[0].strip() for h in next(rows)]
        data = [[float(x) for x in r] for r in rows]
    if "crank_angle" not in head:
        sys.exit(f"{path}: no crank_angle column (a crank-angle grid is needed)")
    return head, data


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    phead, per = read(argv[1])
    thead, tra = read(argv[2])
    patterns = argv[3:] or ["main*.fx", "main*.fy", "mount*.f*"]
    pa, ta = phead.index("crank_angle"), thead.index("crank_angle")
    top = max(round(r[ta]) for r in tra)
    last = {round(r[ta]) % 720: r for r in tra if round(r[ta]) > top - 720}
    pairs = []
    for r in per:
        a = round(r[pa]) % 720
        if a not in last:
            sys.exit(f"{argv[2]}: its last 720 deg have no row at {a} deg")
        pairs.append((r, last[a]))
    for pat in patterns:
        worst, wname = 0.0, "-"
        for name in phead:
            if not fnmatch.fnmatch(name, pat) or name not in thead:
                continue
            i, j = phead.index(name), thead.index(name)
            scale = max(abs(t[j]) for _, t in pairs)
            d = max(abs(p[i] - t[j]) for p, t in pairs) / scale if scale > 0 else 0.0
            if d > worst:
                worst, wname = d, name
        print(f"{pat:10s} {worst:.3g} ({wname})")


if __name__ == "__main__":
    main(sys.argv)
