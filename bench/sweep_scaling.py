#!/usr/bin/env python3
"""Sweeps over local workers and MPI ranks: the section of docs/performance.md
that `make bench` appends after evas_bench has written the file.

Usage: bench/sweep_scaling.py BUILD SCENE >> docs/performance.md

Runs the same 8-point engine speed sweep (1500 to 5000 rpm) serially, with
--jobs 2 and under `mpirun -n 2`, at three lengths of run, repeats each
configuration (interleaved, so that a slow phase of a shared machine does not
fall on one configuration only) and reports the median wall time of the whole
command, the parallel efficiency T1 / (2 T2), the coordinator's overhead per
point and how much two concurrent runs slow each other. Standard library only.
"""
import csv
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

REPEATS = 5
SPEEDS = "157.07963267948966..523.5987755982989:52.35987755982989"  # 1500..5000 rpm


def sweep_cmd(evas, scene, t_end, out, mode):
    cmd = [evas, "study", "sweep", scene, "--t-end", str(t_end), "--sweep",
           "crank.lof.speed=" + SPEEDS, "--channels", "main*.fx,main*.fy",
           "--order-channels", "main3.fx,main3.fy", "--out", out, "--quiet"]
    if mode == "mpi":
        return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2"] + cmd
    return cmd + ["--jobs", "1" if mode == "serial" else "2"]


def run(cmd):
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit("sweep_scaling: %s failed (%d): %s" % (" ".join(cmd), p.returncode, p.stderr))
    return wall


def two_runs(evas, scene, t_end, out, together):
    """Two independent `evas run`s of the scene (3000 rpm), one after the other or
    at once: what this machine gives two processes that share nothing."""
    cmds = [[evas, "run", scene, "--t-end", str(t_end), "--out", out + "-" + k] for k in "ab"]
    t0 = time.monotonic()
    if together:
        procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                 for c in cmds]
        codes = [p.wait() for p in procs]
    else:
        codes = [subprocess.run(c, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
                 for c in cmds]
    wall = time.monotonic() - t0
    if any(codes):
        sys.exit("sweep_scaling: evas run failed (%s) on %s" % (codes, scene))
    return wall


def coordinator_seconds(out):
    """The coordinator's own wall and processor time the sweep reports in sweep.md."""
    with open(os.path.join(out, "sweep.md")) as f:
        for line in f:
            if line.startswith("- coordinator: "):
                words = line.split()
                return float(words[2]), float(words[words.index("time") + 1])
    sys.exit("sweep_scaling: no coordinator line in %s/sweep.md" % out)


def task_walls(out):
    with open(os.path.join(out, "sweep.csv"), newline="") as f:
        return [float(r["wall"]) for r in csv.DictReader(f)]


def main():
    build, scene = sys.argv[1], sys.argv[2]
    evas = os.path.join(build, "evas")
    have_mpi = shutil.which("mpirun") is not None
    modes = ["serial", "jobs2"] + (["mpi"] if have_mpi else [])
    tmp = tempfile.mkdtemp(prefix="evas-sweep-bench.")
    rows = []
    try:
        for t_end in (0.12, 0.6, 1.2):
            walls = {m: [] for m in modes}
            tasks = {m: [] for m in modes}
            coord = []
            pair = {False: [], True: []}
            for r in range(REPEATS):
                for m in modes:
                    out = os.path.join(tmp, "%s-%g-%d" % (m, t_end, r))
                    walls[m].append(run(sweep_cmd(evas, scene, t_end, out, m)))
                    tasks[m].append(task_walls(out))
                    if m == "jobs2":
                        coord.append(coordinator_seconds(out))
                for together in (False, True):
                    out = os.path.join(tmp, "two-%g-%d-%d" % (t_end, r, together))
                    pair[together].append(two_runs(evas, scene, t_end, out, together))
            med = {m: statistics.median(walls[m]) for m in modes}
            med["two"] = statistics.median(pair[False]) / (2 * statistics.median(pair[True]))
            # the serial repeat whose total is the median, for the overhead
            k = walls["serial"].index(sorted(walls["serial"])[REPEATS // 2])
            serial_tasks = sum(tasks["serial"][k])
            # the slowing of a run by a concurrent one: task walls, same repeats
            ratio = [sum(tasks["jobs2"][r]) / sum(tasks["serial"][r]) for r in range(REPEATS)]
            per_task = [b / a for r in range(REPEATS)
                        for a, b in zip(tasks["serial"][r], tasks["jobs2"][r])]
            rows.append((t_end, med, walls, serial_tasks, statistics.median(ratio),
                         min(per_task), max(per_task),
                         statistics.median(c[0] for c in coord),
                         statistics.median(c[1] for c in coord)))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    print("\n## Sweeps over workers and MPI ranks\n")
    print("`evas study sweep` of `%s` over 8 speeds, 1500 to 5000 rpm in steps of 500 rpm "
          "(`--sweep crank.lof.speed=...`), the scene's integrator (IDA, second-order solver, "
          "rtol 1e-5), main-bearing loads kept, order cuts, waterfall and Campbell diagram "
          "drawn: the wall time of the whole command (median of %d, the configurations "
          "interleaved) serially (`--jobs 1`), with two forked workers (`--jobs 2`) and with "
          "`mpirun -n 2` on this 2-core machine. Efficiency = T(serial) / (2 T). "
          "Outside the runs = T(serial) minus the sum of the runs' own wall times (init + "
          "integrate), per point: reading every point's scene before any run, each run's "
          "scene reading and set-up, the files and the figures. Coordinator = the wall time "
          "the coordinator of the `--jobs 2` sweep spent on its own, not waiting for runs, "
          "and its processor time (both in its `sweep.md`): its set-up, the files after "
          "every run, the figures; it runs beside the workers and takes its share of the two "
          "cores, so its wall time is longer than its processor time. Concurrency = sum "
          "of the runs' wall times with `--jobs 2` / serially: how much two runs at once "
          "slow each other (shared caches and memory bandwidth), the median over the "
          "repeats and the range over single runs.\n" % (os.path.relpath(scene), REPEATS))
    head = "| run length | serial [s] | `--jobs 2` [s] | efficiency |"
    sep = "|---:|---:|---:|---:|"
    if have_mpi:
        head += " `mpirun -n 2` [s] | efficiency |"
        sep += "---:|---:|"
    head += (" two independent runs [-] | bound [-] | outside the runs, per point [s] | coordinator wall, processor [s] |"
             " concurrency |")
    sep += "---:|---:|---:|---:|---:|"
    print(head)
    print(sep)
    for t_end, med, walls, serial_tasks, ratio, lo, hi, coord, cpu in rows:
        t1 = med["serial"]
        line = "| %g s | %.2f | %.2f | %.2f |" % (t_end, t1, med["jobs2"], t1 / (2 * med["jobs2"]))
        if have_mpi:
            line += " %.2f | %.2f |" % (med["mpi"], t1 / (2 * med["mpi"]))
        # Amdahl: the coordinator's own wall time does not shrink with workers
        bound = t1 / (2 * (coord + (t1 - coord) / 2))
        line += " %.2f | %.2f | %.3f | %.2f, %.2f | %.2f (%.2f to %.2f) |" % (
            med["two"], bound, (t1 - serial_tasks) / 8, coord, cpu, ratio, lo, hi)
        print(line)
    print("\nTwo independent runs = what this machine gives two processes that share "
          "nothing: two `evas run`s of the scene (3000 rpm, the same run length) one after "
          "the other against both at once, T(one after the other) / (2 T(at once)), median "
          "of %d, interleaved with the sweeps. It is the ceiling for any parallel sweep here "
          "(two virtual cores of a shared host, their caches and memory bandwidth shared)."
          % REPEATS)
    print("\nWith several workers the tasks start longest first (the most output rows of "
          "the crank-angle grid, which grow with the speed like the steps): the costliest "
          "runs do not start last and leave one worker running alone at the end.")
    print("\nBound = the efficiency the serial share alone allows (Amdahl): T1 / (2 (C + "
          "(T1 - C) / 2)) with C the coordinator's wall time above, which two workers do not "
          "shorten (reading every point's scene before any run, the sweep files, the "
          "figures).")
    if not have_mpi:
        print("\n(mpirun was not found: no MPI column.)")
    else:
        # the fixed cost of an MPI start: a 2-point sweep of 1-ms runs
        fixed = {m: [] for m in ("jobs2", "mpi")}
        tmp = tempfile.mkdtemp(prefix="evas-sweep-bench.")
        try:
            for r in range(REPEATS):
                for m in fixed:
                    out = os.path.join(tmp, "%s-%d" % (m, r))
                    cmd = [evas, "study", "sweep", scene, "--t-end", "0.001", "--sweep",
                           "crank.lof.speed=300,310", "--out", out, "--quiet", "--no-plot"]
                    if m == "mpi":
                        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-n", "2"] + cmd
                    else:
                        cmd += ["--jobs", "2"]
                    fixed[m].append(run(cmd))
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        a, b = statistics.median(fixed["mpi"]), statistics.median(fixed["jobs2"])
        print("\nMPI start-up: a 2-point sweep of 1-ms runs takes %.2f s under `mpirun -n 2` "
              "against %.2f s with `--jobs 2` (median of %d): %.2f s per command for mpirun "
              "and MPI_Init/MPI_Finalize, which the MPI column pays on top.\n"
              % (a, b, REPEATS, a - b))

    # projection: 48 points x 6 integrator settings on 64 cores
    t_end, med, walls, serial_tasks, ratio, lo, hi, coord, cpu = rows[-1]
    per_task = cpu / 8  # the coordinator's processor time per run (set-up included: an upper bound)
    run_len = serial_tasks / 8
    tasks = 48 * 6
    waves = -(-tasks // 64)
    t64 = waves * run_len * ratio + tasks * per_task
    t1 = tasks * (run_len + (med["serial"] - serial_tasks) / 8)
    print("\nProjection of a 48-point x 6-integrator sweep (288 runs of %g s of engine time, "
          "each %.2f s alone here) on 64 cores: %d waves of 64 runs, each run slowed by the "
          "measured concurrency factor %.2f (assumed to hold at 64 cores, i.e. memory "
          "bandwidth per core as here), plus the coordinator's processor time of %.3f s per "
          "run (its set-up and figures spread over the 8 runs measured: an upper bound), "
          "taken as not overlapping the runs at all: %.0f s against %.0f s on one core, a speed-up of %.0f "
          "(efficiency %.2f). The coordinator's share is what limits it (%.0f s of the %.0f); "
          "with runs of realistic length (1 to 120 s of engine time, 3 to 400 s each) it is "
          "small. Assumed further: runs of equal cost (IDA's cost grows with speed, 1.0 to "
          "1.9x here, so the slowest wave sets the time), one rank per core, the scene and "
          "body files on a shared file system.\n"
          % (t_end, run_len, waves, ratio, per_task, t64, t1, t1 / t64, t1 / (64 * t64),
             tasks * per_task, t64))


if __name__ == "__main__":
    main()
