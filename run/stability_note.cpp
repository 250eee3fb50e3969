#include "run/stability_note.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

#include "integrators/settings.h"
#include "solver/system.h"

namespace evas {

HighestFrequency highest_frequency(Problem& p, double t, const Vec& q, const Vec& v) {
  HighestFrequency out;
  const int n = p.size();
  if (n == 0 || n > 1500 || p.has_mass() || p.constraint_count() > 0) return out;
  SpMat K = p.jacobian_pattern(), C = p.jacobian_pattern();
  p.force_jacobian(t, q.data(), v.data(), K, C);
  const Mat Kd = Mat(K);
  if (!Kd.allFinite()) return out;
  const Eigen::EigenSolver<Mat> es(Kd, true);
  if (es.info() != Eigen::Success) return out;
  Eigen::Index top = 0;
  es.eigenvalues().cwiseAbs().maxCoeff(&top);
  const double lam = std::abs(es.eigenvalues()[top]);
  if (!(lam > 0.0)) return out;
  out.omega = std::sqrt(lam);
  const Eigen::VectorXcd x = es.eigenvectors().col(top);
  Eigen::Index i = 0;
  x.cwiseAbs().maxCoeff(&i);
  out.coordinate = static_cast<int>(i);
  // the bodies' own modal stiffness in that mode against the whole
  SpMat KB = p.jacobian_pattern(), CB = p.jacobian_pattern();
  KB.coeffs().setZero();
  CB.coeffs().setZero();
  p.body_operator(t, KB, CB);
  const std::complex<double> whole = x.adjoint() * (Kd.cast<std::complex<double>>() * x);
  const std::complex<double> bodies = x.adjoint() * (Mat(KB).cast<std::complex<double>>() * x);
  if (std::abs(whole) > 0.0)
    out.element_share = std::clamp(1.0 - std::abs(bodies) / std::abs(whole), 0.0, 1.0);
  return out;
}

std::string stability_limit_note(Problem& p, const IntegratorSettings& s, double t, const Vec& q,
                                 const Vec& v) {
  if (!takes_fixed_steps(s) || !(s.step > 0.0)) return "";
  const IntegratorCapabilities caps = integrator_capabilities(s.name);
  if (!caps.stability_limit) return "";
  const double limit = caps.stability_limit(s);
  if (!std::isfinite(limit)) return "";
  const HighestFrequency hf = highest_frequency(p, t, q, v);
  if (!(hf.omega > 0.0) || !(s.step * hf.omega > limit)) return "";
  std::ostringstream os;
  os.precision(4);
  os << s.name << " is stable for h omega <= " << limit << " (the undamped oscillator); the step "
     << s.step << " s gives h omega = " << s.step * hf.omega << " for the highest frequency of the "
     << "model linearized at t = " << t << " s, " << hf.omega / (2.0 * M_PI) << " Hz ("
     << p.describe_coordinate(hf.coordinate) << " moves most; "
     << std::lround(100.0 * hf.element_share)
     << " % of its stiffness from the elements' forces, the rest the bodies' own modes): "
     << "the step amplifies that mode; a step of at most " << limit / hf.omega
     << " s is stable for it";
  return os.str();
}

std::string stability_limit_warning(Model& model, const IntegratorSettings& s, double t0) {
  if (!takes_fixed_steps(s)) return "";
  const IntegratorCapabilities caps = integrator_capabilities(s.name);
  if (!caps.stability_limit || !std::isfinite(caps.stability_limit(s))) return "";
  System sys(model);
  Vec q, v;
  sys.initial_state(q, v);
  try {
    return stability_limit_note(sys, s, t0, q, v);
  } catch (const std::exception&) {
    return "";  // the run itself reports a state the elements refuse
  }
}

}  // namespace evas
