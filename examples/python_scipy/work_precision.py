#!/usr/bin/env python3
"""Work-precision of SciPy's implicit solvers on an evas model against IDA.

SciPy's Radau (Radau IIA order 5, Hairer & Wanner's RADAU5) and BDF (variable
order 1-5) solve the demo scene's first-order form y' = rhs(t, y) with evas's
analytic Jacobian (Model.rhs_jacobian); evas's IDA runs the same scene at the
same tolerances. Error: the largest difference over the scene's output channels
and times relative to each channel's peak, against IDA at rtol 1e-10. Writes
OUT/work_precision.csv and OUT/work_precision.png (docs/extending.md).

    python3 examples/python_scipy/work_precision.py [SCENE] [--t-end T] [--out DIR]
"""
import argparse
import os
import time

import numpy as np
import scipy.integrate

import evas


def error(values, ref):
    peak = np.abs(ref).max(axis=0)
    keep = peak > 0
    return (np.abs(values - ref)[:, keep] / peak[keep]).max()


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene", nargs="?", default=os.path.join(here, "..", "..", "scenes", "demo.yaml"))
    ap.add_argument("--t-end", type=float, default=0.02)
    ap.add_argument("--out", default="work-precision-python")
    ap.add_argument("--rtols", default="1e-3,1e-4,1e-5,1e-6,1e-7")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)

    m = evas.Model(a.scene)
    n = m.size
    ref = m.run("ida", {"rtol": 1e-10, "atol": 1e-13}, t_end=a.t_end)
    if ref["status"] != "completed":
        raise SystemExit("reference run failed: " + ref["status"])
    times = ref["time"]
    q0, v0 = m.initial_state()
    y0 = np.concatenate([q0, v0])
    rows = []
    for rtol in [float(x) for x in a.rtols.split(",")]:
        atol = rtol * 1e-3
        r = m.run("ida", {"rtol": rtol, "atol": atol}, t_end=a.t_end)
        rows.append(("ida", rtol, error(r["values"], ref["values"]), r["stats"]["wall_seconds"],
                     r["stats"]["steps"]))
        for method in ("Radau", "BDF"):
            start = time.perf_counter()
            sol = scipy.integrate.solve_ivp(m.rhs, (times[0], times[-1]), y0, method=method,
                                            t_eval=times, rtol=rtol, atol=atol,
                                            jac=m.rhs_jacobian)
            wall = time.perf_counter() - start
            if not sol.success:
                rows.append(("scipy-" + method, rtol, float("nan"), wall, 0))
                continue
            vals = np.array([m.outputs(t, y[:n], y[n:]) for t, y in zip(sol.t, sol.y.T)])
            rows.append(("scipy-" + method, rtol, error(vals, ref["values"]), wall, sol.nfev))
    with open(os.path.join(a.out, "work_precision.csv"), "w") as f:
        f.write("solver,rtol,error,wall_s,steps_ida_or_rhs_evals_scipy\n")
        for r in rows:
            f.write("%s,%g,%.6e,%.6f,%d\n" % r)
    for r in rows:
        print("%-13s rtol %-7g error %.3e  wall %.4f s" % r[:4])
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no figure")
        return
    fig, ax = plt.subplots(figsize=(6, 4.5))
    for name in ("ida", "scipy-Radau", "scipy-BDF"):
        pts = [(r[2], r[3]) for r in rows if r[0] == name and np.isfinite(r[2])]
        if pts:
            e, w = zip(*pts)
            ax.loglog(e, w, "o-", label=name)
    ax.set_xlabel("error (max over channels and times, relative to the peak)")
    ax.set_ylabel("wall time [s]")
    ax.set_title("%s, %.3g s: SciPy on evas's residual and Jacobian vs IDA" % (m.name, a.t_end))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "work_precision.png"), dpi=120)
    print("figure:", os.path.join(a.out, "work_precision.png"))


if __name__ == "__main__":
    main()
