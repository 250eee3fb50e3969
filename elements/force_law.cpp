#include "elements/force_law.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace evas {

ForceLaw ForceLaw::polynomial(std::vector<double> coeffs) {
  ForceLaw f;
  f.kind_ = Kind::Polynomial;
  f.c_ = std::move(coeffs);
  return f;
}

ForceLaw ForceLaw::table(std::vector<double> d, std::vector<double> f, Interp interp,
                         const std::string& where) {
  if (d.size() != f.size())
    throw InputError(where + ": table has " + std::to_string(d.size()) + " deflections but " +
                     std::to_string(f.size()) + " forces");
  if (d.size() < 2)
    throw InputError(where + ": table needs at least two (deflection, force) pairs, got " +
                     std::to_string(d.size()));
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!std::isfinite(d[i]) || !std::isfinite(f[i]))
      throw InputError(where + ": table entry " + std::to_string(i) + " is not finite");
    if (i > 0 && !(d[i] > d[i - 1])) {
      std::ostringstream os;
      os << where << ": table deflections must increase strictly, but entry " << i << " (" << d[i]
         << " m) follows " << d[i - 1] << " m";
      throw InputError(os.str());
    }
  }
  ForceLaw law;
  law.kind_ = Kind::Table;
  law.interp_ = interp;
  law.x_ = std::move(d);
  law.y_ = std::move(f);
  const std::size_t n = law.x_.size();
  std::vector<double> h(n - 1), s(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = law.x_[k + 1] - law.x_[k];
    s[k] = (law.y_[k + 1] - law.y_[k]) / h[k];
  }
  law.m_.assign(n, 0.0);
  law.m_[0] = s[0];
  law.m_[n - 1] = s[n - 2];
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (s[k - 1] * s[k] <= 0.0) {
      law.m_[k] = 0.0;  // local extremum or flat: keep the interpolant flat here
    } else {
      const double w1 = 2.0 * h[k] + h[k - 1], w2 = h[k] + 2.0 * h[k - 1];
      law.m_[k] = (w1 + w2) / (w1 / s[k - 1] + w2 / s[k]);
    }
  }
  return law;
}

ForceLaw ForceLaw::table_pairs(const std::vector<double>& pairs, Interp interp,
                               const std::string& where) {
  if (pairs.size() % 2 != 0)
    throw InputError(where + ": table must list (deflection, force) pairs, got an odd count of " +
                     std::to_string(pairs.size()) + " numbers");
  std::vector<double> d, f;
  for (std::size_t i = 0; i + 1 < pairs.size(); i += 2) {
    d.push_back(pairs[i]);
    f.push_back(pairs[i + 1]);
  }
  return table(std::move(d), std::move(f), interp, where);
}

ForceLaw::Interp ForceLaw::interp_from_name(const std::string& name, const std::string& where) {
  if (name == "linear") return Interp::Linear;
  if (name == "pchip") return Interp::Pchip;
  throw InputError(where + ": interpolation '" + name + "' is not one of: linear, pchip");
}

void ForceLaw::eval(double d, double& f, double& df) const {
  if (kind_ == Kind::Polynomial) {
    // Horner on f(d) = d (k1 + d (k2 + d k3 ...)).
    double p = 0.0, dp = 0.0;
    for (std::size_t k = c_.size(); k-- > 0;) {
      dp = dp * d + p;
      p = p * d + c_[k];
    }
    f = p * d;
    df = p + dp * d;
    return;
  }
  const std::size_t n = x_.size();
  if (d <= x_[0]) {
    df = m_[0];
    f = y_[0] + df * (d - x_[0]);
    return;
  }
  if (d >= x_[n - 1]) {
    df = m_[n - 1];
    f = y_[n - 1] + df * (d - x_[n - 1]);
    return;
  }
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), d) - x_.begin()) - 1;
  const double h = x_[k + 1] - x_[k];
  const double t = (d - x_[k]) / h;
  if (interp_ == Interp::Linear) {
    df = (y_[k + 1] - y_[k]) / h;
    f = y_[k] + df * (d - x_[k]);
    return;
  }
  const double t2 = t * t, t3 = t2 * t;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2,
               h11 = t3 - t2;
  const double g00 = 6 * t2 - 6 * t, g10 = 3 * t2 - 4 * t + 1, g01 = -6 * t2 + 6 * t,
               g11 = 3 * t2 - 2 * t;
  f = h00 * y_[k] + h10 * h * m_[k] + h01 * y_[k + 1] + h11 * h * m_[k + 1];
  df = (g00 * y_[k] + g01 * y_[k + 1]) / h + g10 * m_[k] + g11 * m_[k + 1];
}

double ForceLaw::value(double d) const {
  double f, df;
  eval(d, f, df);
  return f;
}

double ForceLaw::slope(double d) const {
  double f, df;
  eval(d, f, df);
  return df;
}

double ForceLaw::scale() const {
  double s = 0.0;
  for (double c : c_) s = std::max(s, std::abs(c));
  for (double y : y_) s = std::max(s, std::abs(y));
  return s;
}

ClearanceLaw::ClearanceLaw(ForceLaw law, double gap, double smoothing, const std::string& where)
    : law_(std::move(law)), gap_(gap), w_(smoothing) {
  if (!(gap >= 0.0) || !std::isfinite(gap))
    throw InputError(where + ": gap must be >= 0 m, got " + std::to_string(gap));
  if (!(smoothing >= 0.0) || !std::isfinite(smoothing))
    throw InputError(where + ": smoothing must be >= 0 m, got " + std::to_string(smoothing));
}

void ClearanceLaw::smooth(double e, double& rho, double& drho) const {
  if (e <= 0.0) {
    rho = drho = 0.0;
  } else if (e >= w_) {
    rho = e;
    drho = 1.0;
  } else {
    const double x = e / w_;
    rho = e * x * (2.0 - x);     // 2 e^2/w - e^3/w^2
    drho = x * (4.0 - 3.0 * x);  // 4 e/w - 3 e^2/w^2
  }
}

void ClearanceLaw::eval(double d, double& g, double& dg) const {
  const double e = std::abs(d) - gap_;
  if (e <= 0.0) {
    g = dg = 0.0;
    return;
  }
  double rho, drho, f, df;
  smooth(e, rho, drho);
  law_.eval(rho, f, df);
  g = d > 0.0 ? f : -f;
  dg = df * drho;  // sign(d)^2 = 1
}

void ClearanceLaw::contact(double d, double& chi, double& dchi) const {
  const double e = std::abs(d) - gap_;
  if (e <= 0.0) {
    chi = dchi = 0.0;
  } else if (e >= w_) {
    chi = 1.0;
    dchi = 0.0;
  } else {
    const double x = e / w_;
    chi = x * x * (3.0 - 2.0 * x);
    dchi = (d > 0.0 ? 1.0 : -1.0) * 6.0 * x * (1.0 - x) / w_;
  }
}

ForceLaw make_force_law(const std::string& kind, const std::vector<double>& coeffs,
                        const std::vector<double>& pairs, const std::string& interp,
                        const std::string& where) {
  if (kind == "polynomial") {
    if (!pairs.empty())
      throw InputError(where + ": a table is given but law is 'polynomial' (set law: table)");
    return ForceLaw::polynomial(coeffs);
  }
  if (kind == "table") {
    if (pairs.empty())
      throw InputError(where + ": law 'table' needs a table of (deflection, force) pairs");
    return ForceLaw::table_pairs(pairs, ForceLaw::interp_from_name(interp, where), where);
  }
  throw InputError(where + ": law '" + kind + "' is not one of: polynomial, table");
}

}  // namespace evas
