#include "elements/spring_damper.h"

namespace evas {

SpringDamper::SpringDamper(std::string name, std::vector<int> markers, const Vec3& k, const Vec3& c,
                           const Vec3& kr, const Vec3& cr, const Vec3& l0, const Vec3& preload)
    : Element(std::move(name), std::move(markers)),
      k_(k),
      c_(c),
      kr_(kr),
      cr_(cr),
      l0_(l0),
      preload_(preload) {}

void SpringDamper::evaluate(double, const MarkerMotion* m, MarkerLoad* loads) const {
  const Mat3& R = m[0].R;
  const Vec3 dp = m[1].p - m[0].p;
  const Vec3 d = R.transpose() * dp - l0_;
  const Vec3 dv = R.transpose() * (m[1].v - m[0].v);
  const Vec3 r = R.transpose() * (m[1].psi - m[0].psi);
  const Vec3 dw = R.transpose() * (m[1].w - m[0].w);
  const Vec3 F2 = R * (-(k_.cwiseProduct(d) + c_.cwiseProduct(dv)) - preload_);
  const Vec3 M2 = R * (-(kr_.cwiseProduct(r) + cr_.cwiseProduct(dw)));
  loads[1].F = F2;
  loads[1].M = M2;
  loads[0].F = -F2;
  loads[0].M = -M2 - dp.cross(F2);
}

void SpringDamper::derivatives(double t, const MarkerMotion* m, Mat& D) const {
  (void)t;
  const Mat3& R = m[0].R;
  const Mat3 Kg = R * k_.asDiagonal() * R.transpose();
  const Mat3 Cg = R * c_.asDiagonal() * R.transpose();
  const Mat3 Krg = R * kr_.asDiagonal() * R.transpose();
  const Mat3 Crg = R * cr_.asDiagonal() * R.transpose();
  const Vec3 dp = m[1].p - m[0].p;
  const Vec3 F2 = R * (-(k_.cwiseProduct(R.transpose() * dp - l0_) +
                         c_.cwiseProduct(R.transpose() * (m[1].v - m[0].v))) -
                       preload_);
  D.setZero();
  // Columns: marker j at 12 j: p, v, psi, w. Rows: F1, M1, F2, M2.
  for (int j = 0; j < 2; ++j) {
    const double s = j == 1 ? 1.0 : -1.0;  // d(dp)/dp_j = s I
    const int c0 = 12 * j;
    D.block<3, 3>(6, c0) = -s * Kg;                  // dF2/dp_j
    D.block<3, 3>(6, c0 + 3) = -s * Cg;              // dF2/dv_j
    D.block<3, 3>(9, c0 + 6) = -s * Krg;             // dM2/dpsi_j
    D.block<3, 3>(9, c0 + 9) = -s * Crg;             // dM2/dw_j
    D.block<3, 12>(0, c0) = -D.block<3, 12>(6, c0);  // F1 = -F2
    // M1 = -M2 - skew(dp) F2
    D.block<3, 12>(3, c0) = -D.block<3, 12>(9, c0) - skew(dp) * D.block<3, 12>(6, c0);
    D.block<3, 3>(3, c0) += s * skew(F2);
  }
}

std::vector<Channel> SpringDamper::channels() const {
  return {{"fx", "N"},   {"fy", "N"}, {"fz", "N"}, {"mx", "N m"}, {"my", "N m"},
          {"mz", "N m"}, {"dx", "m"}, {"dy", "m"}, {"dz", "m"}};
}

void SpringDamper::channel_values(double t, const MarkerMotion* m, double* out) const {
  MarkerLoad loads[2];
  evaluate(t, m, loads);
  const Mat3& R = m[0].R;
  const Vec3 F = R.transpose() * loads[1].F, M = R.transpose() * loads[1].M;
  const Vec3 d = R.transpose() * (m[1].p - m[0].p) - l0_;
  for (int i = 0; i < 3; ++i) {
    out[i] = F[i];
    out[3 + i] = M[i];
    out[6 + i] = d[i];
  }
}

}  // namespace evas
