#include "elements/element.h"

#include <cmath>

namespace evas {

void Element::derivatives(double t, const MarkerMotion* motion, Mat& D) const {
  derivatives_fd(t, motion, D);
}

void Element::derivatives_fd(double t, const MarkerMotion* motion, Mat& D) const {
  const std::size_t k = markers_.size();
  std::vector<MarkerMotion> m(motion, motion + k);
  std::vector<MarkerLoad> lp(k), lm(k);
  D.setZero(6 * k, 12 * k);
  auto component = [](MarkerMotion& mm, int c) -> double& {
    Vec3* parts[4] = {&mm.p, &mm.v, &mm.psi, &mm.w};
    return (*parts[c / 3])[c % 3];
  };
  for (std::size_t j = 0; j < k; ++j)
    for (int c = 0; c < 12; ++c) {
      double& x = component(m[j], c);
      const double x0 = x;
      const double h = 1e-6 * std::max(1.0, std::abs(x0));
      x = x0 + h;
      evaluate(t, m.data(), lp.data());
      x = x0 - h;
      evaluate(t, m.data(), lm.data());
      x = x0;
      for (std::size_t i = 0; i < k; ++i) {
        D.block<3, 1>(6 * i, 12 * j + c) = (lp[i].F - lm[i].F) / (2 * h);
        D.block<3, 1>(6 * i + 3, 12 * j + c) = (lp[i].M - lm[i].M) / (2 * h);
      }
    }
}

}  // namespace evas
