#!/usr/bin/env python3
"""Main-bearing loads of a run-up as it passes a speed, against a steady run.

usage: runup_compare.py RUNUP.csv STEADY.csv W0 W1 T W [--cycles N]

RUNUP.csv and STEADY.csv are `evas run --csv` results on the crank-angle grid
(one row per degree). The run-up's crank speed is the two-knot profile of the
scene's LOF, W0 -> W1 rad/s over T s: a monotone cubic with zero end slopes
(Fritsch & Carlson 1980), w(t) = W0 + (W1 - W0)(3x^2 - 2x^3), x = t/T. The
cycle of 720 deg centred where the run-up passes W is compared, degree by
degree at the same crank angle modulo 720, with the steady run's last
cycle. Prints a Markdown table of max |run-up - steady| / max |steady| per
main-bearing force channel, and the speed range and angular acceleration
inside the compared cycle. Standard library only.
"""
import csv
import math
import sys


def read(path):
    with open(path, newline="") as f:
        rows = csv.reader(f)
        head = [h.split("[")[0] for h in next(rows)]
        data = [[float(x) for x in r] for r in rows]
    return head, data


def speed(t, w0, w1, T):
    if t <= 0:
        return w0
    if t >= T:
        return w1
    x = t / T
    return w0 + (w1 - w0) * (3 * x * x - 2 * x ** 3)


def angle(t, w0, w1, T):
    """Integral of speed() from 0 [rad]."""
    if t >= T:
        return T * (w0 + 0.5 * (w1 - w0)) + w1 * (t - T)
    x = t / T
    return T * (w0 * x + (w1 - w0) * (x ** 3 - 0.5 * x ** 4))


def main(argv):
    if len(argv) < 7:
        sys.exit(__doc__)
    ru_path, st_path = argv[1], argv[2]
    w0, w1, T, w = (float(a) for a in argv[3:7])
    if not (min(w0, w1) < w < max(w0, w1)):
        sys.exit("runup_compare.py: W must lie between W0 and W1")
    lo, hi = 0.0, T  # the time the run-up passes w (speed is monotone)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if (speed(mid, w0, w1, T) - w) * (w1 - w0) < 0:
            lo = mid
        else:
            hi = mid
    t_star = 0.5 * (lo + hi)
    centre = math.degrees(angle(t_star, w0, w1, T))

    head, ru = read(ru_path)
    head_st, st = read(st_path)
    if head != head_st:
        sys.exit("runup_compare.py: the two files have different channels")
    ia = head.index("crank_angle")
    steady_end = st[-1][ia]
    steady = {}
    for r in st:
        if r[ia] > steady_end - 720.0 - 1e-6:
            steady[round(r[ia]) % 720] = r
    window = [r for r in ru if abs(r[ia] - centre) <= 360.0 - 1e-9]
    if len(window) < 700 or len(steady) < 720:
        sys.exit("runup_compare.py: the runs do not cover a whole cycle at that speed")
    times = [r[0] for r in window]
    speeds = [speed(t, w0, w1, T) for t in times]
    rpm = 30.0 / math.pi
    print(
        "Run-up cycle centred at t = %.4f s (crank angle %.0f deg): speed %.0f .. %.0f rpm,"
        " angular acceleration %.0f rad/s^2 at its centre; steady run: its last cycle."
        % (t_star, centre, min(speeds) * rpm, max(speeds) * rpm,
           (speed(t_star + 1e-6, w0, w1, T) - speed(t_star - 1e-6, w0, w1, T)) / 2e-6))
    print()
    print("| channel | max abs steady [kN] | max abs difference [kN] | relative |")
    print("|---|---:|---:|---:|")
    worst = 0.0
    for c, name in enumerate(head):
        if not (name.startswith("main") and name.endswith((".fx", ".fy"))):
            continue
        scale = max(abs(r[c]) for r in steady.values())
        diff = max(abs(r[c] - steady[round(r[ia]) % 720][c]) for r in window)
        worst = max(worst, diff / scale)
        print("| %s | %.2f | %.2f | %.3f |" % (name, scale / 1e3, diff / 1e3, diff / scale))
    print()
    print("largest relative difference: %.3f" % worst)


if __name__ == "__main__":
    main(sys.argv)
