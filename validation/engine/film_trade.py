#!/usr/bin/env python3
"""The film trade on the validation engine: tables from film_trade.sh's runs.

usage: film_trade.py OUT_DIR

OUT_DIR/case<c>/<film>/<integrator>/ hold one run each (results.csv, summary.json,
and <integrator>.wall, the whole process's wall time in seconds). Over the last
720 deg of each run, against the reynolds film (same case, integrator ida):
  - loads: the largest difference of the ten main-bearing load channels
    (main1..5 .fx, .fy) divided by that channel's half peak-to-peak in the
    reynolds run, over the whole waveform and in the engine orders up to 12
    (validation/engine/bearing_difference.py's measure), with the channel;
  - orbit: the largest distance between the journal centres (ex, ey) of the
    two runs, divided by the clearance (30 um);
  - the largest eccentricity ratio, the smallest film h_min and the five
    bearings' friction power averaged over the cycle, of each film.
Then each integrator's steps and wall time with each film.
Standard library only.
"""
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bearing_difference import low_orders, read  # noqa: E402

CLEARANCE = 3e-5
FILMS = ["short", "finite", "reynolds", "reynolds-grid36", "reynolds-groove36", "reynolds-grid"]
INTEGRATORS = [("ida", "ida"), ("cvode", "cvode"), ("ga", "generalized-alpha adaptive"),
               ("radau", "radau adaptive"), ("hht", "hht-alpha 5 us"), ("newmark", "newmark 5 us"),
               ("bathe", "bathe 5 us"), ("linacc", "linear-acceleration 5 us"),
               ("arkode", "arkode"), ("cd", "central-difference 0.2 us")]


def last_cycle(path):
    head, rows = read(path)
    ia = head.index("crank_angle")
    last = rows[-1][ia]
    window = [r for r in rows if r[ia] >= last - 720.0 - 1e-9]
    return head, window


def col(head, rows, name):
    return [r[head.index(name)] for r in rows]


def run_dir(out, case, film, integ):
    return os.path.join(out, f"case{case}", film, integ)


def stats(d):
    try:
        with open(os.path.join(d, "summary.json")) as f:
            s = json.load(f)
        with open(d + ".wall") as f:
            wall = float(f.read())
        return s.get("status", "?"), s["stats"]["steps"], wall
    except (OSError, KeyError, ValueError):
        return "missing", None, None


def compare(out, case):
    ref = os.path.join(run_dir(out, case, "reynolds", "ida"), "results.csv")
    if not os.path.exists(ref):
        print(f"Case {case}: no reynolds run ({ref})\n")
        return
    rh, rw = last_cycle(ref)
    names = [f"main{b}.{c}" for b in range(1, 6) for c in ("fx", "fy")]
    amp = {n: 0.5 * (max(col(rh, rw, n)) - min(col(rh, rw, n))) for n in names}
    print(f"**Case {case}** (last 720 deg of 0.24 s, IDA rtol 1e-5; differences against "
          "reynolds)\n")
    print("| film | loads, whole waveform | loads, orders <= 12 | orbit / c | largest eps | "
          "smallest h_min [um] | friction power [W] | steps | wall [s] |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for film in FILMS:
        d = run_dir(out, case, film, "ida")
        path = os.path.join(d, "results.csv")
        if not os.path.exists(path):
            continue
        h, w = last_cycle(path)
        whole, orders = (0.0, ""), (0.0, "")
        if len(w) == len(rw):
            for n in names:
                a, b = col(rh, rw, n), col(h, w, n)
                e = max(abs(x - y) for x, y in zip(a, b)) / amp[n]
                if e >= whole[0]:
                    whole = (e, n)
                fa, fb = low_orders(a[:-1], 12), low_orders(b[:-1], 12)
                e = max(abs(x - y) for x, y in zip(fa, fb)) / amp[n]
                if e >= orders[0]:
                    orders = (e, n)
        orbit = 0.0
        for b in range(1, 6):
            ex, ey = col(h, w, f"main{b}.ex"), col(h, w, f"main{b}.ey")
            rx, ry = col(rh, rw, f"main{b}.ex"), col(rh, rw, f"main{b}.ey")
            if len(ex) == len(rx):
                orbit = max(orbit, max(math.hypot(a - c, bb - dd)
                                       for a, bb, c, dd in zip(ex, ey, rx, ry)) / CLEARANCE)
        eps = max(max(col(h, w, f"main{b}.eps")) for b in range(1, 6))
        hmin = min(min(col(h, w, f"main{b}.h_min")) for b in range(1, 6))
        power = sum(sum(col(h, w, f"main{b}.friction_power")) / len(w) for b in range(1, 6))
        status, steps, wall = stats(d)
        ref_cell = "(reference)" if film == "reynolds" else None
        print(f"| {film} | {ref_cell or f'{whole[0]:.3f} ({whole[1]})'} | "
              f"{ref_cell or f'{orders[0]:.3f} ({orders[1]})'} | "
              f"{ref_cell or f'{orbit:.3f}'} | {eps:.3f} | {hmin * 1e6:.2f} | {power:.1f} | "
              f"{steps if steps is not None else '-'} | "
              f"{f'{wall:.1f}' if wall is not None else '-'} |")
    print()


def integrators(out, case):
    print(f"**Case {case}: steps and whole-process wall time [s] of each integrator**\n")
    print("| integrator | " + " | ".join(FILMS[:3]) + " |")
    print("|---|" + "---:|" * 3)
    for key, label in INTEGRATORS:
        cells = []
        for film in FILMS[:3]:
            status, steps, wall = stats(run_dir(out, case, film, key))
            if steps is None:
                cells.append("-")
            elif status != "completed":
                cells.append(f"{status}")
            else:
                cells.append(f"{steps:,} / {wall:.1f} s")
        if any(c != "-" for c in cells):  # the rest of the catalogue runs Case 1 only
            print(f"| {label} | " + " | ".join(cells) + " |")
    print()


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__)
    for case in (1, 2):
        compare(argv[1], case)
        integrators(argv[1], case)


if __name__ == "__main__":
    main(sys.argv)
