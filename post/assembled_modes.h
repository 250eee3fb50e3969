// Natural frequencies of the assembled, linearized system: the Campbell
// diagram of the whole engine (bodies, mounts, driveline couplings and the
// bearing films together), where post/natural_frequencies.h gives each body's
// own modes and the rigid engine on its mounts.
//
// Linearization. The problem's equations qdd + f(t, q, v) = 0
// (model/problem.h) about states (t_i, q_i, v_i) of the operating cycle give
// dqdd = -K_i dq - C_i dv, K = df/dq, C = df/dv (the bearing films' stiffness
// and damping at the journal's place in the cycle, the mounts', the
// couplings'). A periodic operating point has no single linearization (the
// film stiffness swings by orders of magnitude over a cycle); the modes are
// those of the cycle-averaged matrices K = mean K_i, C = mean C_i (the
// time-invariant part of the periodic system; Hill's method to zeroth order,
// parametric resonances left out), with the states given (e.g. 36 states
// spread over the steady cycle). The first-order matrix A = [0 I; -K -C] is
// solved densely (Eigen's EigenSolver); each complex pair lambda = -zeta
// omega_n +- i omega_d gives a mode at f = omega_d / (2 pi) [Hz] (the damped
// frequency, the one a spectrum shows) with damping ratio zeta = -Re(lambda) /
// |lambda|. Over-damped roots and f <= f_min are left out.
//
// Labels. Every coordinate is modal, at unit modal mass (explicit rigid modes
// too), so |x_q,i|^2 of the mode's displacement part is coordinate i's share
// of its kinetic energy. The share is summed per body and per kind (the
// body's explicit rigid modes by direction tx, ty, tz, rx, ry, rz, and its
// elastic modes); the largest group names the mode:
//   "mount"     the rigid motion of a body an engine-mount carries;
//   "driveline" the rigid rotation of a body a motor element (a dynamometer,
//               a coupling) acts on;
//   "body"      elastic modes of a body (rigid motion of any other body too).
// e.g. "driveline: crank rigid rx 97%", "mount: block rigid tz 61%",
// "body: crank elastic 88%".
//
// Not handled (the reason is returned and no modes): constraints (joints),
// quasi-static coordinates, element internal states.
#pragma once

#include <string>
#include <vector>

#include "model/model.h"
#include "model/problem.h"

namespace evas {

struct AssembledMode {
  double hz = 0.0;             ///< damped natural frequency [Hz]
  double damping_ratio = 0.0;  ///< zeta
  std::string where;           ///< "mount", "driveline" or "body"
  std::string label;           ///< e.g. "driveline: crank rigid rx 97%"
  double share = 0.0;          ///< the naming group's share of the kinetic energy
};

struct AssembledModes {
  std::vector<AssembledMode> modes;  ///< ascending in frequency
  std::string reason;                ///< not empty: why there are none
  int states = 0;                    ///< linearization states averaged
};

/// The modes of `problem` (the System of `model`) linearized about the states
/// (t[i], q of qv[i] = [q; v]) averaged (see above), f_min < f <= f_max [Hz].
AssembledModes assembled_modes(Problem& problem, const Model& model, const std::vector<double>& t,
                               const std::vector<Vec>& qv, double f_max, double f_min = 0.5);

}  // namespace evas
