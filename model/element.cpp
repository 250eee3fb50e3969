#include "model/element.h"

#include <algorithm>
#include <cmath>

namespace evas {

namespace {

// Central differences over every motion component (p, v, psi, w of each
// marker): eval(m) at the plus, then the minus point, store(col, h) after each.
template <class Eval, class Store>
void motion_differences(std::vector<MarkerMotion>& m, Eval&& eval, Store&& store) {
  for (std::size_t j = 0; j < m.size(); ++j)
    for (int c = 0; c < 12; ++c) {
      Vec3* parts[4] = {&m[j].p, &m[j].v, &m[j].psi, &m[j].w};
      double& x = (*parts[c / 3])[c % 3];
      const double x0 = x;
      const double h = 1e-6 * std::max(1.0, std::abs(x0));
      x = x0 + h;
      eval(true);
      x = x0 - h;
      eval(false);
      x = x0;
      store(12 * static_cast<int>(j) + c, h);
    }
}

}  // namespace

void Element::derivatives(double t, const MarkerMotion* motion, Mat& D) const {
  derivatives_fd(t, motion, D);
}

void Element::derivatives_fd(double t, const MarkerMotion* motion, Mat& D) const {
  const std::size_t k = markers_.size();
  std::vector<MarkerMotion> m(motion, motion + k);
  std::vector<MarkerLoad> lp(k), lm(k);
  D.setZero(6 * k, 12 * k);
  motion_differences(
      m, [&](bool plus) { evaluate(t, m.data(), plus ? lp.data() : lm.data()); },
      [&](int col, double h) {
        for (std::size_t i = 0; i < k; ++i) {
          D.block<3, 1>(6 * i, col) = (lp[i].F - lm[i].F) / (2 * h);
          D.block<3, 1>(6 * i + 3, col) = (lp[i].M - lm[i].M) / (2 * h);
        }
      });
}

std::string Element::internal_name(int i) const { return "z" + std::to_string(i); }

void Element::internal_derivatives_fd(double t, const MarkerMotion* motion, const double* z,
                                      Mat& Dz, Mat& Hm, Mat& Hz) const {
  const std::size_t k = markers_.size();
  const int nz = internal_count();
  std::vector<MarkerMotion> m(motion, motion + k);
  std::vector<double> zz(z, z + nz), hp(static_cast<std::size_t>(nz)),
      hm(static_cast<std::size_t>(nz));
  std::vector<MarkerLoad> lp(k), lm(k);
  Dz.setZero(6 * static_cast<int>(k), nz);
  Hm.setZero(nz, 12 * static_cast<int>(k));
  Hz.setZero(nz, nz);
  motion_differences(
      m, [&](bool plus) { internal_rate(t, m.data(), zz.data(), plus ? hp.data() : hm.data()); },
      [&](int col, double h) {
        for (int i = 0; i < nz; ++i)
          Hm(i, col) =
              (hp[static_cast<std::size_t>(i)] - hm[static_cast<std::size_t>(i)]) / (2 * h);
      });
  for (int c = 0; c < nz; ++c) {
    double& x = zz[static_cast<std::size_t>(c)];
    const double x0 = x;
    const double h = 1e-6 * std::max(1.0, std::abs(x0));
    x = x0 + h;
    internal_rate(t, m.data(), zz.data(), hp.data());
    evaluate_z(t, m.data(), zz.data(), lp.data());
    x = x0 - h;
    internal_rate(t, m.data(), zz.data(), hm.data());
    evaluate_z(t, m.data(), zz.data(), lm.data());
    x = x0;
    for (int i = 0; i < nz; ++i)
      Hz(i, c) = (hp[static_cast<std::size_t>(i)] - hm[static_cast<std::size_t>(i)]) / (2 * h);
    for (std::size_t i = 0; i < k; ++i) {
      Dz.block<3, 1>(6 * static_cast<int>(i), c) = (lp[i].F - lm[i].F) / (2 * h);
      Dz.block<3, 1>(6 * static_cast<int>(i) + 3, c) = (lp[i].M - lm[i].M) / (2 * h);
    }
  }
}

}  // namespace evas
