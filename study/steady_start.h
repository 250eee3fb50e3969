// A study on the steady cycle (`evas study ... --steady`, `--initial FILE`):
// every run, the reference's included, starts from one state written into the
// scene's text (each body's `initial: {q, v}`), so the runs are the same
// initial-value problem and the error a study measures is the integration
// error alone, not mixed with the start-up transient.
//
//   --initial FILE   the state of FILE (io/initial_state.h: evas periodic's
//                    DIR/state.yaml), the scene's end time as it is;
//   --steady         the scene's periodic state (evas periodic's projected
//                    method, the scene's own integrator, defect --steady-tol)
//                    or FILE's, and one period from it: the study's runs are
//                    the steady cycle.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "study/scene_edit.h"

namespace evas::study {

struct SteadyStart {
  std::string initial_file;  ///< --initial FILE ("" none)
  bool steady = false;       ///< one period from the periodic state
  double tol = 3e-4;         ///< periodicity defect of the state evas finds
};

/// What the runs start from, for the study's files.
struct StartedFrom {
  std::string description;    ///< "" = the scene's own initial state
  std::vector<double> state;  ///< every body's q, then v ("" = scene's own)
  std::string state_text;     ///< the state as an evas state file (initial_state.h)
};

/// Changes `src` as `how` says (nothing when neither is given): every body's
/// initial q and v set to the state, and with steady the end time one period
/// after the scene's start. Throws InputError for a scene with no period, a
/// state file that does not fit it, or a periodic search that does not
/// converge (its message). `log` (may be null) gets a progress line.
StartedFrom start_from(SceneSource& src, const SteadyStart& how, const std::function<bool()>& stop,
                       std::ostream* log);

}  // namespace evas::study
