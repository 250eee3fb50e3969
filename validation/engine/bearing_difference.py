#!/usr/bin/env python3
"""Main-bearing loads of runs against a reference run, per channel.

usage: bearing_difference.py [--orders N] REF.csv RUN.csv [RUN.csv ...]

Each file is an `evas run --csv` result of the validation engine on its
crank-angle grid (one row per degree; docs/engine-bodies.md, "Modal
convergence"). Over the reference's last 720 deg, for every main-bearing
force channel (main1..5 .fx, .fy): max |F_run - F_ref| / A, with A half the
reference's peak-to-peak in that window (its amplitude about its middle).
Prints a Markdown table, one row per run and its largest channel. Rows are
matched by crank angle; a run that ended early is compared over the angles it
reached within the window, and said so. With --orders N both waveforms are
first reduced to their engine orders up to N (the Fourier series over the
720 deg window, harmonics k/2 <= N; the window must then be complete in both).
Standard library only.
"""
import cmath
import csv
import sys


def low_orders(vals, n_orders):
    """The Fourier series of one 720-deg cycle (samples at 0..719 deg of it)
    kept up to engine order n_orders (harmonic k of the cycle is order k/2)."""
    n = len(vals)
    out = [0.0] * n
    for k in range(0, 2 * int(n_orders) + 1):
        if 2 * k > n:
            break
        c = sum(v * cmath.exp(-2j * cmath.pi * k * i / n) for i, v in enumerate(vals)) / n
        w = 1.0 if k == 0 or 2 * k == n else 2.0
        for i in range(n):
            out[i] += w * (c * cmath.exp(2j * cmath.pi * k * i / n)).real
    return out


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
    orders = None
    if len(argv) > 2 and argv[1] == "--orders":
        orders = float(argv[2])
        argv = argv[:1] + argv[3:]
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
            if orders is None:
                errs.append(max(abs(b[d] - a[c]) for a, b in matched) / amp[n])
                continue
            if len(matched) != len(window):
                sys.exit(f"{path}: --orders needs the whole 720-deg window")
            # one cycle: the window's first 720 rows (the last row repeats the first angle)
            fa = low_orders([a[c] for a, _ in matched[:-1]], orders)
            fb = low_orders([b[d] for _, b in matched[:-1]], orders)
            errs.append(max(abs(x - y) for x, y in zip(fa, fb)) / amp[n])
        k = max(range(len(names)), key=lambda i: errs[i])
        note = "" if len(matched) == len(window) else f" ({len(matched)} of {len(window)} angles)"
        print(f"| {path}{note} | " + " | ".join(f"{e:.2e}" for e in errs) +
              f" | {errs[k]:.2e} ({names[k]}) |")


if __name__ == "__main__":
    main(sys.argv)
