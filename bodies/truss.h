// Test bodies that need no external FE program: a space truss of point masses
// and axial bars shaped as a straight beam (square cross-section, `segments`
// bays along x, each bay braced by face and internal diagonals).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "model/types.h"

namespace evas {

/// Largest accepted `segments` (400 004 nodes, 1.2 million DOF).
inline constexpr int kMaxTrussSegments = 100000;
/// A generated body: every mode (no elastic count) needs the dense eigen-solver,
/// O(DOF^2) memory and O(DOF^3) time, so at most this many DOF; and at most this
/// many modes in any case.
inline constexpr long kMaxDenseDof = 3000;
inline constexpr long kMaxGeneratedModes = 1000;

struct TrussBeamSpec {
  int segments = 10;           ///< bays along x, 1..kMaxTrussSegments
  double length = 1.0;         ///< [m]
  double width = 0.05;         ///< side of the square cross-section [m]
  double youngs = 2.1e11;      ///< bar modulus [Pa]
  double area = 2e-5;          ///< bar cross-section [m^2]
  double density = 7850.0;     ///< bar density [kg/m^3], mass lumped half to each end node
  Vec3 origin = Vec3::Zero();  ///< position of the first cross-section's centre [m]
};

/// Nodal data of an FE-like model: what an importer or generator hands to the builder.
struct FeModel {
  std::vector<long> node_ids;
  Eigen::Matrix<double, Eigen::Dynamic, 3> s;  ///< N x 3 [m]
  SpMat K;                                     ///< 3N x 3N stiffness, DOF 3*i + a
  SpMat Ms;                                    ///< N x N scalar mass (M = Ms (x) I3)
  std::map<std::string, std::vector<long>> node_sets;
};

/// Node ids 1..N; node sets "end0", "end1" (first/last cross-section),
/// "section<k>" (k = 0..segments) and "all".
FeModel make_truss_beam(const TrussBeamSpec& spec);

}  // namespace evas
