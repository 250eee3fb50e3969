// Common numeric types and small helpers shared by every stage of evas.
// Units: SI throughout (m, kg, s, N, rad).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <stdexcept>
#include <string>

namespace evas {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;
using SpMat = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

/// Skew matrix: skew(x) * y == x.cross(y).
inline Mat3 skew(const Vec3& x) {
  Mat3 s;
  s << 0.0, -x.z(), x.y(), x.z(), 0.0, -x.x(), -x.y(), x.x(), 0.0;
  return s;
}

/// Rotation matrix of a rotation vector (Rodrigues).
Mat3 rotation_from_vector(const Vec3& phi);
/// Rotation vector of a rotation matrix (inverse of rotation_from_vector, |phi| <= pi).
Vec3 vector_from_rotation(const Mat3& R);

/// A number with enough digits to locate a failure ("0.0123456789").
std::string format_number(double x);

/// Error raised for bad input: the message names the file, the item and what is wrong.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Error raised when a run fails numerically (the message names time, element and state).
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A state outside the range in which an element's law holds (a film that
/// closes, a journal turned off its bearing axis, pulleys without a common
/// tangent). Newton trial iterates and too-long steps reach such states; the
/// integrators treat it as a failed step and retry with a smaller one (SUNDIALS:
/// a recoverable error), and report it when they cannot get past it.
class RangeError : public RunError {
 public:
  using RunError::RunError;
};

}  // namespace evas
