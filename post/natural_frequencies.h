// Natural frequencies of a scene's model, for a Campbell diagram.
//
// Two kinds:
//  - "elastic": every modal body's elastic modes (ModeKind::Elastic),
//    f = sqrt(lambda) / (2 pi), up to f_max; mode = the index among the body's
//    modes (as `evas info` numbers them).
//  - "mount": the six rigid-body modes of the engine on its mounts. The bodies
//    carried by `engine-mount` elements (marker 1, the block side) and every
//    other body that can move rigidly (explicit rigid modes, e.g. the crankshaft
//    in its bearings) are taken as ONE rigid body: main bearings and liners are
//    orders of magnitude stiffer than the mounts (engine: film stiffness ~1e8 -
//    1e9 N/m against mounts of ~1e5 N/m), so the engine's low modes are those of
//    a rigid engine on the mounts. A body on the support side (marker 0) of a
//    mount (e.g. a subframe) is not part of the engine; its markers, like the
//    ground's, are held fixed. The crank's spin is ignored (no gyroscopic
//    terms), and the crank's polar inertia counts as if it turned with the
//    block (a crank on frictionless bearings does not; the roll mode about the
//    crank axis is then slightly low). Mass, centre of mass and inertia
//    are the bodies' MassProperties (of the full body) at the initial LOF pose.
//    The mounts are linearised at the initial state (time t0, the bodies' q0,
//    v0) through Element::derivatives(): the stiffness of any force law,
//    orientation, rotational stiffness and preload; dampers are left out and a
//    Maxwell branch counts with its static (unloaded) stiffness, i.e. not at all.
//    The 6 x 6 mass and stiffness matrices are taken about the common centre of
//    mass in G axes, coordinates (u, theta): translation of that point and small
//    rotation. The stiffness includes the lever-arm term of loads present at the
//    initial state (preloads), and is symmetrised. f = sqrt(max(lambda, 0)) /
//    (2 pi) of K x = lambda M x (an unstable direction thus shows as 0 Hz).
//    All six are returned, whatever f_max; none when the model has no mount
//    carrying a body.
#pragma once

#include <string>
#include <vector>

#include "model/model.h"

namespace evas {

struct NaturalFrequency {
  std::string body;       ///< body name; mount modes: the mounted bodies, joined by '+'
  std::string kind;       ///< "elastic" or "mount"
  int mode = 0;           ///< elastic: index among the body's modes; mount: 0..5, ascending
  double hz = 0.0;        ///< [Hz]
  std::string direction;  ///< mount: dominant component x, y, z, rx, ry, rz (G axes); elastic: ""
  double share = 0.0;     ///< mount: that component's share of the mode (0..1); elastic: 0
};

/// The rigid engine on its mounts (see above).
struct MountModes {
  std::vector<int> bodies;             ///< the bodies taken as one rigid body
  std::vector<int> mounts;             ///< engine-mount elements that act on them
  Vec3 point = Vec3::Zero();           ///< common point: their centre of mass (G) [m]
  double mass = 0.0;                   ///< [kg]
  Mat3 inertia = Mat3::Zero();         ///< about `point`, G axes [kg m^2]
  Eigen::Matrix<double, 6, 6> M, K;    ///< mass and stiffness, coordinates (u, theta)
  std::vector<double> hz;              ///< 6 frequencies, ascending (empty: no mounts)
  Eigen::Matrix<double, 6, 6> shapes;  ///< columns: mode shapes, M-normalised
  std::vector<std::string> direction;  ///< dominant component per mode
  std::vector<double> share;           ///< its share of sum_i M_ii x_i^2
};

/// The six mount modes at time t0 (empty hz when no engine-mount carries a body).
/// Throws InputError when the bodies have no positive-definite mass matrix.
MountModes mount_modes(const Model& model, double t0 = 0.0);

/// Mount modes first (ascending), then each body's elastic modes up to f_max
/// [Hz] (inclusive), in body and mode order. Throws InputError for f_max < 0 or
/// not finite.
std::vector<NaturalFrequency> natural_frequencies(const Model& model, double f_max,
                                                  double t0 = 0.0);

}  // namespace evas
