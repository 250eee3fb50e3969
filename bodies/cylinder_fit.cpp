// Least-squares cylinder centre of a node set (cylinder_fit.h).
#include "bodies/cylinder_fit.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace evas {

namespace {

// Circle fit in the plane normal to `axis` (unit); infinite rms when degenerate.
CylinderFit fit_about(const std::vector<Vec3>& pts, const Vec3& axis, const Vec3& mean) {
  CylinderFit fit;
  fit.axis = axis;
  fit.rms = std::numeric_limits<double>::infinity();
  // in-plane basis
  const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 e1 = axis.cross(helper).normalized();
  const Vec3 e2 = axis.cross(e1);
  const std::size_t n = pts.size();
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  double axial = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 d = pts[i] - mean;
    const double x = d.dot(e1), y = d.dot(e2);
    A(static_cast<Eigen::Index>(i), 0) = x;
    A(static_cast<Eigen::Index>(i), 1) = y;
    A(static_cast<Eigen::Index>(i), 2) = 1.0;
    b(static_cast<Eigen::Index>(i)) = -(x * x + y * y);
    axial += d.dot(axis) / static_cast<double>(n);
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 3) return fit;
  const Eigen::Vector3d s = qr.solve(b);
  const double cx = -0.5 * s[0], cy = -0.5 * s[1];
  const double r2 = cx * cx + cy * cy - s[2];
  if (!(r2 > 0.0)) return fit;
  fit.radius = std::sqrt(r2);
  fit.centre = mean + cx * e1 + cy * e2 + axial * axis;
  double sum = 0.0;
  for (const Vec3& p : pts) {
    const Vec3 d = p - fit.centre;
    const double dist = (d - d.dot(axis) * axis).norm();
    sum += (dist - fit.radius) * (dist - fit.radius);
  }
  fit.rms = std::sqrt(sum / static_cast<double>(n));
  return fit;
}

}  // namespace

CylinderFit fit_cylinder(const std::vector<Vec3>& points, const Vec3* axis) {
  if (points.size() < 3)
    throw InputError("cylinder fit: " + std::to_string(points.size()) +
                     " nodes, at least 3 are needed");
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  CylinderFit best;
  best.rms = std::numeric_limits<double>::infinity();
  if (axis) {
    if (!(axis->norm() > 0.0)) throw InputError("cylinder fit: the axis is zero");
    best = fit_about(points, axis->normalized(), mean);
  } else {
    Mat3 cov = Mat3::Zero();
    for (const Vec3& p : points) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Mat3> es(cov);
    for (int k = 0; k < 3; ++k) {
      const CylinderFit f = fit_about(points, es.eigenvectors().col(k).normalized(), mean);
      if (f.rms < best.rms) best = f;
    }
    // The principal direction of an unevenly meshed surface is tilted from the
    // axis: refine the direction by a pattern search on two tilt angles that
    // minimises the radial RMS (exact for points on a cylinder).
    if (std::isfinite(best.rms)) {
      double step = 0.05;
      while (step > 1e-12 && best.rms > 0.0) {
        const Vec3 a = best.axis;
        const Vec3 e1 = a.cross(std::abs(a.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized();
        const Vec3 e2 = a.cross(e1);
        bool better = false;
        const Vec3 dirs[4] = {e1, -e1, e2, -e2};
        for (const Vec3& d : dirs) {
          const CylinderFit f = fit_about(points, (a + step * d).normalized(), mean);
          if (f.rms < best.rms) {
            best = f;
            better = true;
            break;
          }
        }
        if (!better) step *= 0.5;
      }
    }
  }
  if (!std::isfinite(best.rms))
    throw InputError("cylinder fit: the nodes do not determine a circle about any axis");
  return best;
}

}  // namespace evas
