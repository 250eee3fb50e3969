#include "model/types.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace evas {

Mat3 rotation_from_vector(const Vec3& phi) {
  const double a = phi.norm();
  if (a < 1e-300) return Mat3::Identity() + skew(phi);
  return Eigen::AngleAxisd(a, phi / a).toRotationMatrix();
}

Vec3 vector_from_rotation(const Mat3& R) {
  Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

std::string format_number(double x) {
  std::ostringstream os;
  os << std::setprecision(10) << x;
  return os.str();
}

}  // namespace evas
