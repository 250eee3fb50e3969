// A model's state as a file of its own: every body's modal coordinates q and
// velocities v (the scene's `initial: {q, v}` of each body), written by `evas
// periodic` (DIR/state.yaml, the periodic state) and read by `--initial FILE`
// of `evas run` and `evas periodic`, so that a run starts from a steady cycle
// (a run-up from the steady state at its first speed; a neighbour's state as
// the start of a periodic search).
//
//   # comment lines
//   scene: engine-case1          (informative)
//   t: 0                         (the time of the state [s], informative)
//   bodies:
//     - {name: crank, q: [...], v: [...]}
//     - {name: block, q: [...], v: [...]}
#pragma once

#include <string>

#include "model/model.h"

namespace evas {

/// x[0 .. n) as a YAML flow list at 17 significant digits (reads back to the bit).
std::string exact_list_text(const double* x, int n);

/// The text of the state file: `comment` lines first (each prefixed "# "),
/// the numbers at 17 significant digits (they read back to the bit).
std::string initial_state_text(const Model& model, const Vec& q, const Vec& v,
                               const std::string& scene, double t, const std::string& comment);

/// Sets every body's q0 and v0 from the file. Throws InputError naming the
/// file and the item: a body the model does not have, a body of the model the
/// file leaves out, a length that is not the body's number of modes, a value
/// that is not a finite number.
void apply_initial_state(Model& model, const std::string& path);

}  // namespace evas
