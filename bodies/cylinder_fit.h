// Centre of a cylindrical node set (a journal surface, a bearing bore, a
// liner): the least-squares circle about the set's axis, at the set's mean
// axial position. A surface set's node centroid lies off the axis by the
// mesh's irregularity (a millimetre on a coarse tet mesh, against a film
// clearance of tens of micrometres); the fitted centre lies on the axis to
// the accuracy of the node positions.
//
// Axis: the given one, or else the principal direction of the node cloud
// (one of the three eigenvectors of its covariance) about which the circle
// fits best, refined by a pattern search on two tilt angles that minimises the
// RMS radial deviation. Circle: the algebraic (Kasa) fit, minimising
// sum (x^2 + y^2 + D x + E y + F)^2 in the plane normal to the axis (I. Kasa,
// IEEE Trans. Instrum. Meas. 25 (1976) 8-14), exact for nodes on a circle.
#pragma once

#include <vector>

#include "model/types.h"

namespace evas {

struct CylinderFit {
  Vec3 centre = Vec3::Zero();  ///< on the axis, at the mean axial position of the nodes
  Vec3 axis = Vec3::UnitZ();   ///< unit
  double radius = 0.0;
  double rms = 0.0;  ///< RMS of (distance to the axis - radius) over the nodes
};

/// Fits the nodes' positions (at least 3 not on one line in the plane normal
/// to the axis). `axis` = nullptr: found as described above. Throws InputError
/// when the points do not determine a circle.
CylinderFit fit_cylinder(const std::vector<Vec3>& points, const Vec3* axis = nullptr);

}  // namespace evas
