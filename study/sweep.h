// `evas study sweep`: a grid of operating points (docs/study.md, "Sweeps").
//
// Every --sweep ITEM.KEY=VALUES (repeatable; the cartesian product, the first
// key varying slowest) changes the scene as --param does; each grid point runs
// once with the scene's integrator, or once per case of --case specs. The runs
// are the study's tasks (task.h), so they go to the study's runner: one after
// another, --jobs local processes or MPI ranks, with the same files.
//
// Files in the output folder:
//   points/NNNN.h5   one per task (point x case), written as it ends: the
//                    point's assignments, the case, status, message, wall,
//                    statistics and the selected channels (time, crank angle,
//                    values). They are the sweep's record: --resume keeps the
//                    completed ones, --point I writes one (a batch array job)
//                    and --merge builds the sweep files from them.
//   sweep.h5         the grid, every task's status, statistics and channels,
//                    order spectra of every channel (crank-angle grid), the
//                    mean speed of every point and the Campbell data;
//                    rewritten (atomically) at most every 10 s while tasks
//                    end, and at the end.
//   sweep.csv, .md   the table.
//   order_cuts.png, waterfall.png, campbell.png, and their .gp scripts.
#pragma once

#include "study/study.h"

namespace evas::study {

struct SweepOptions {
  std::vector<std::string> sweeps;  ///< "ITEM.KEY=VALUES" (parse_sweep)
  std::vector<CaseInput> cases;     ///< none: the scene's integrator
  std::string order_channels;       ///< globs of the figures' channels ("": the first channel)
  std::vector<double> orders = {1.0, 2.0, 4.0};  ///< orders of the order cuts
  double max_order = 12.0;  ///< orders kept in the spectra and drawn in the Campbell diagram
  int cycles = 1;           ///< engine cycles (at the end of each run) per spectrum
  int point = -1;           ///< >= 0: run this task only (into points/), no sweep files
  bool merge = false;       ///< run nothing: build the sweep files from points/
  bool resume = false;      ///< keep the completed tasks of points/, run the rest
  /// "" every point a transient run to the scene's end; else every point the
  /// periodic cycle by this method of evas periodic (run/periodic.h), defect
  /// tolerance periodic_tol: the spectra are the steady cycle's
  std::string periodic;
  double periodic_tol = 3e-4;
  /// With periodic: each point's search starts from the periodic state of the
  /// point before it (of the same case, in the grid's order), run in chains as
  /// wide as the runner (docs/study.md); false: every point from the scene's
  /// own initial state
  bool warm_start = true;
};

struct SweepTask {
  int point = 0;                    ///< grid point
  int case_index = 0;               ///< case of the point
  std::vector<std::string> values;  ///< value of each key at the point
  CaseResult result;                ///< status, message, wall, statistics (error: NaN)
  RunData data;                     ///< the channels
  std::string worker;               ///< where it ran
  /// How a periodic point's search started: "point N" (a warm start from that
  /// point's periodic state) or "" (the scene's initial state)
  std::string start;
  double rpm = std::numeric_limits<double>::quiet_NaN();  ///< mean crank speed [rpm]
};

struct SweepResult {
  StudyInfo info;
  std::vector<std::string> keys;  ///< swept ITEM.KEYs
  std::vector<Case> cases;
  std::vector<SweepTask> tasks;  ///< point-major: task = point * cases + case
  std::string runner;            ///< how the tasks ran
  /// The points' plausibility warnings (Scene::warnings, as evas run gives
  /// them), "point P (KEY=V): warning", said before any run
  std::vector<std::string> warnings;
  int resumed = 0;  ///< tasks taken from an earlier run (--resume)
  /// Wall time the coordinator spent on its own (setup, reading every point's
  /// scene, files, figures), not waiting for runs [s].
  double coordinator_seconds = 0.0;
  /// Its parts [s]: reading the scene (bodies, tables) before anything else;
  /// checking every point's scene; after the runs (natural frequencies,
  /// sweep.h5, figures). The rest is the files written as results come in.
  double setup_seconds = 0.0, check_seconds = 0.0, finish_seconds = 0.0;
  /// Its processor time over the whole sweep, when the runs were in other
  /// processes (workers, ranks); NaN otherwise [s].
  double coordinator_cpu_seconds = std::numeric_limits<double>::quiet_NaN();
};

/// Runs (or merges) the sweep; writes the files above. Throws InputError for
/// bad input (a key that matches nothing, a value the scene refuses, a folder
/// that already holds a sweep without --resume or --merge).
SweepResult sweep(const Options& opt, const SweepOptions& so);

/// Task file name of task i: "points/0007.h5".
std::string task_file_name(int i);

}  // namespace evas::study
