// The periodic solution of a problem with periodic forcing (periodic.h).
#include "run/periodic.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "integrators/sundials_util.h"
#include "run/stop.h"
#include "solver/quasi_static.h"

namespace evas::run {

namespace {

using Clock = std::chrono::steady_clock;
using cd = std::complex<double>;

// The floor of a coordinate's scale, relative to the largest of its kind.
constexpr double kScaleFloor = 1e-4;

// The statistics of whole runs summed: the counters a SUNDIALS segment has
// (sundials::add_segment), then the rest.
void add_stats(IntegratorStats& sum, const IntegratorStats& s) {
  sundials::add_segment(sum, s);
  sum.restarts += s.restarts;
  sum.refused_states += s.refused_states;
  sum.substeps += s.substeps;
  sum.max_step_iterations = std::max(sum.max_step_iterations, s.max_step_iterations);
  sum.wall_seconds += s.wall_seconds;
  sum.last_step = s.last_step;
  sum.last_order = s.last_order;
  sum.min_step = sum.min_step > 0.0 && s.min_step > 0.0 ? std::min(sum.min_step, s.min_step)
                                                        : std::max(sum.min_step, s.min_step);
  sum.max_step = std::max(sum.max_step, s.max_step);
  sum.max_constraint = std::max(sum.max_constraint, s.max_constraint);
  sum.max_constraint_rate = std::max(sum.max_constraint_rate, s.max_constraint_rate);
}

// The state x = (q, v) as one vector and back.
Vec join(const Vec& q, const Vec& v) {
  Vec x(q.size() + v.size());
  x << q, v;
  return x;
}

// What coordinate i of the state x = (q, v) is.
std::string state_name(const Problem& p, int i) {
  const int n = p.size();
  return (i < n ? "q of " : "v of ") + p.describe_coordinate(i < n ? i : i - n);
}

class Solver {
 public:
  Solver(Problem& p, double t0, double T, const IntegratorSettings& s, const PeriodicOptions& o,
         std::vector<double> samples, CycleObserver* obs)
      : p_(p), t0_(t0), T_(T), set_(s), opt_(o), samples_(std::move(samples)), obs_(obs) {
    n_ = p.size();
    if (samples_.empty())
      for (int k = 0; k < 64; ++k) samples_.push_back(t0 + T * k / 64.0);
    scale_ = Vec::Ones(2 * n_);
  }

  PeriodicResult solve(const Vec& q0, const Vec& v0);

 private:
  // One cycle from x at t0; the state at t0 + T. `main`: an iterate's cycle
  // (observed, its samples kept for the scales and the linearization).
  Vec cycle(const Vec& x, bool main);
  // max_i |r_i| / scale_i and the coordinate that sets it.
  double defect(const Vec& r, int& worst) const;
  void update_scale();
  void record(PeriodicResult& res, const std::string& step, const Vec& r);
  // projected: the slow subspace and its first Jacobian from the linearization
  void build_projection(PeriodicResult& res);
  void linearized_multipliers(PeriodicResult& res, const Linearization& lin);
  std::vector<std::string> lives_in(const Eigen::VectorXcd& x) const;
  // The monodromy matrix at x (G(x) = gx) by one-sided differences of the
  // cycle map (2n cycles); its eigenvalues become res.multipliers.
  Mat monodromy_by_differences(PeriodicResult& res, const Vec& x, const Vec& gx);

  Problem& p_;
  double t0_, T_;
  IntegratorSettings set_;
  bool coarse_ = false;  // the cycles are integrated at the coarse tolerances
  PeriodicOptions opt_;
  std::vector<double> samples_;
  CycleObserver* obs_;
  int n_ = 0;
  int cycles_ = 0;
  Vec scale_;
  std::vector<Vec> sq_, sv_;  // the last main cycle's sampled states
  std::vector<double> st_;
  IntegratorStats stats_;
  Clock::time_point clock0_ = Clock::now();
  // projected
  Mat V_, L_, H_;
  // the cycle the linearization was built from (its sampled states), kept for
  // a finer one when a step from the coarse one leaves the model's states
  std::vector<Vec> lq_, lv_;
  std::vector<double> lt_;
  bool refined_ = false;
};

Vec Solver::cycle(const Vec& x, bool main) {
  ++cycles_;
  Vec q = x.head(n_), v = x.tail(n_);
  const std::unique_ptr<Integrator> integ = make_integrator(set_.name);
  if (main) {
    if (obs_) obs_->begin(cycles_ - 1);
    sq_.clear();
    sv_.clear();
    st_.clear();
  }
  const double t_end = t0_ + T_;
  std::vector<double> outs;
  if (main)
    for (double t : samples_)
      if (t > t0_ + 1e-12 * T_ && t < t_end - 1e-12 * T_) outs.push_back(t);
  auto keep = [&](double t, const Vec& qq, const Vec& vv) {
    if (!main) return;
    if (obs_) obs_->state(t, qq, vv);
    st_.push_back(t);
    sq_.push_back(qq);
    sv_.push_back(vv);
  };
  try {
    settle_quasi_static(p_, t0_, q, v);
    start_internal_states(p_, t0_, q, v);
    IntegratorSettings s = set_;
    if (coarse_) {
      s.rtol *= opt_.coarse;
      s.atol *= opt_.coarse;
    }
    integ->init(p_, t0_, q, v, s);
    if (obs_) integ->set_step_monitor([this](double t, double h) { obs_->between_steps(t, h); });
    if (main && !samples_.empty() && std::abs(samples_.front() - t0_) <= 1e-12 * T_)
      keep(t0_, q, v);
    integrate(*integ, p_, t0_, outs, keep);
    // the cycle's end, landed on exactly (stops before it honoured)
    double t = outs.empty() ? t0_ : outs.back();
    while (true) {
      const double stop = p_.next_stop(t);
      if (stop < t_end - 1e-12 * T_) {
        integ->advance(stop, true, q, v);
        t = stop;
        if (p_.at_stop(t, q.data(), v.data())) integ->restart(t, q, v);
        continue;
      }
      integ->advance(t_end, true, q, v);
      break;
    }
  } catch (const InputError&) {
    throw;
  } catch (const Stopped&) {
    add_stats(stats_, integ->stats());
    throw;
  } catch (const std::exception& e) {
    add_stats(stats_, integ->stats());
    throw RunError("cycle " + std::to_string(cycles_) + " of the periodic solution (" +
                   to_text(opt_.method) + "): " + e.what());
  }
  add_stats(stats_, integ->stats());
  return join(q, v);
}

void Solver::update_scale() {
  if (sq_.empty()) return;
  Vec amp = Vec::Zero(2 * n_);
  for (std::size_t k = 0; k < sq_.size(); ++k)
    for (int i = 0; i < n_; ++i) {
      amp[i] = std::max(amp[i], std::abs(sq_[k][i]));
      amp[n_ + i] = std::max(amp[n_ + i], std::abs(sv_[k][i]));
    }
  const double qmax = n_ ? amp.head(n_).maxCoeff() : 0.0;
  const double vmax = n_ ? amp.tail(n_).maxCoeff() : 0.0;
  for (int i = 0; i < 2 * n_; ++i) {
    const double floor = kScaleFloor * (i < n_ ? qmax : vmax);
    scale_[i] = std::max({amp[i], floor, 1e-300});
  }
}

double Solver::defect(const Vec& r, int& worst) const {
  double d = 0.0;
  worst = 0;
  for (int i = 0; i < r.size(); ++i) {
    const double e = std::abs(r[i]) / scale_[i];
    if (e > d) {
      d = e;
      worst = i;
    }
  }
  return d;
}

void Solver::record(PeriodicResult& res, const std::string& step, const Vec& r) {
  PeriodicIteration it;
  int worst = 0;
  it.cycles = cycles_;
  it.defect = defect(r, worst);
  it.worst = state_name(p_, worst);
  it.step = step;
  it.wall = std::chrono::duration<double>(Clock::now() - clock0_).count();
  res.iterations.push_back(it);
}

std::vector<std::string> Solver::lives_in(const Eigen::VectorXcd& x) const {
  std::vector<std::pair<double, int>> share;
  for (int i = 0; i < x.size(); ++i) share.emplace_back(std::abs(x[i]) / scale_[i], i);
  std::sort(share.begin(), share.end(), [](auto& a, auto& b) { return a.first > b.first; });
  std::vector<std::string> out;
  const double top = share.empty() ? 0.0 : share.front().first;
  for (std::size_t k = 0; k < share.size() && k < 3; ++k)
    if (share[k].first >= 0.3 * top) out.push_back(state_name(p_, share[k].second));
  return out;
}

void Solver::linearized_multipliers(PeriodicResult& res, const Linearization& lin) {
  std::vector<int> order(lin.mu.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  auto mod = [&](int k) { return std::abs(lin.mu[static_cast<std::size_t>(k)]); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return mod(a) > mod(b); });
  res.multipliers.clear();
  for (std::size_t k = 0; k < order.size() && k < 12; ++k) {
    const int j = order[k];
    FloquetMultiplier f;
    f.mu = lin.mu[static_cast<std::size_t>(j)];
    f.lives_in = lives_in(lin.X.col(j));
    res.multipliers.push_back(f);
  }
  res.multiplier_source = lin.source + " (an estimate)";
}

void Solver::build_projection(PeriodicResult& res) {
  if (!refined_) {
    lt_ = st_;
    lq_ = sq_;
    lv_ = sv_;
  }
  const Linearization lin = opt_.linearization == "averaged"
                                ? averaged_linearization(p_, T_, lt_, lq_, lv_)
                                : stepped_linearization(p_, t0_, T_, lt_, lq_, lv_, opt_.steps);
  const int N = 2 * n_;
  std::vector<int> pick;
  for (int j = 0; j < N; ++j) {
    const cd m = lin.mu[static_cast<std::size_t>(j)];
    if (std::abs(m) < opt_.slow) continue;
    if (m.imag() < 0.0) continue;  // the conjugate's real and imaginary parts serve both
    pick.push_back(j);
  }
  const Eigen::MatrixXcd Y = lin.X.inverse();  // rows: left eigenvectors
  std::vector<Vec> vcols, wrows;
  for (int j : pick) {
    const cd m = lin.mu[static_cast<std::size_t>(j)];
    vcols.push_back(lin.X.col(j).real());
    wrows.push_back(Y.row(j).real().transpose());
    if (m.imag() > 0.0) {
      vcols.push_back(lin.X.col(j).imag());
      wrows.push_back(-Y.row(j).imag().transpose());
    }
  }
  const int pdim = static_cast<int>(vcols.size());
  res.slow_dimension = pdim;
  V_.resize(N, pdim);
  Mat W(pdim, N);
  for (int k = 0; k < pdim; ++k) {
    // columns scaled to unit size in the scaled state norm
    const double nrm = vcols[static_cast<std::size_t>(k)].cwiseQuotient(scale_).norm();
    V_.col(k) = vcols[static_cast<std::size_t>(k)] / (nrm > 0.0 ? nrm : 1.0);
    W.row(k) = wrows[static_cast<std::size_t>(k)].transpose();
  }
  if (pdim > 0) {
    L_ = (W * V_).fullPivLu().solve(W);  // z = L x: coordinates in V of the spectral projection
    H_ = L_ * lin.Phi * V_;              // the monodromy on the slow subspace, in the basis V
  }
  linearized_multipliers(res, lin);
}

Mat Solver::monodromy_by_differences(PeriodicResult& res, const Vec& x, const Vec& gx) {
  const int N = 2 * n_;
  Mat Phi(N, N);
  const double rel = std::max(std::sqrt(set_.rtol), 1e-7);
  for (int j = 0; j < N; ++j) {
    Vec xp = x;
    const double h = rel * scale_[j];
    xp[j] += h;
    Phi.col(j) = (cycle(xp, false) - gx) / h;
  }
  Eigen::EigenSolver<Mat> es(Phi);
  std::vector<int> order(static_cast<std::size_t>(N));
  for (int k = 0; k < N; ++k) order[static_cast<std::size_t>(k)] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(es.eigenvalues()[a]) > std::abs(es.eigenvalues()[b]);
  });
  res.multipliers.clear();
  for (int k = 0; k < N && k < 12; ++k) {
    FloquetMultiplier f;
    f.mu = es.eigenvalues()[order[static_cast<std::size_t>(k)]];
    f.lives_in = lives_in(es.eigenvectors().col(order[static_cast<std::size_t>(k)]));
    res.multipliers.push_back(f);
  }
  res.multiplier_source = "eigenvalues of the monodromy matrix by differences of the cycle map";
  return Phi;
}

PeriodicResult Solver::solve(const Vec& q0, const Vec& v0) {
  PeriodicResult res;
  if (p_.constraint_count() > 0)
    throw InputError(
        "the periodic solution takes no constraints (joints): use the penalty formulation "
        "(--set formulation=penalty)");
  if (p_.internal_count() > 0)
    throw InputError("the periodic solution does not yet take element internal states (" +
                     p_.internal_name(0) + ", " + std::to_string(p_.internal_count()) + " in all)");
  if (opt_.method == PeriodicMethod::projected && (!p_.quasi_static().empty() || p_.has_mass()))
    throw InputError(
        "the projected method linearizes qdd = -f: it does not take quasi-static modes or a mass "
        "matrix; use --method anderson");
  if (!(opt_.tol > 0.0)) throw InputError("the periodicity tolerance must be positive");
  if (opt_.max_cycles < 2) throw InputError("at least two cycles are needed (max cycles)");
  const int N = 2 * n_;
  // newton's differences of the cycle map need one tolerance throughout
  coarse_ = opt_.coarse > 1.0 && opt_.method != PeriodicMethod::newton;
  Vec x = join(q0, v0);
  Vec gx = cycle(x, true);
  update_scale();
  Vec r = gx - x;
  record(res, coarse_ ? "start (coarse)" : "start", r);
  // Anderson's history
  std::vector<Vec> hist_g, hist_f;
  // the previous iterate, for the secant update
  Vec x_prev, g_prev;
  bool have_lin = false;
  bool mixed = false;  // gx is the first at the settings' tolerances, the history's coarse
  std::string note;    // said of the next step
  while (true) {
    int worst = 0;
    const double d = defect(r, worst);
    if (!coarse_ && d <= opt_.tol) {
      res.converged = true;
      break;
    }
    bool to_fine = false;
    if (coarse_ && d <= 30.0 * opt_.tol) {
      // near enough: the next cycles at the settings' own tolerances
      coarse_ = false;
      to_fine = true;
    }
    if (cycles_ >= opt_.max_cycles) break;
    std::string step;
    Vec xn;
    switch (opt_.method) {
      case PeriodicMethod::fixed_point:
        xn = gx;
        step = "fixed point";
        break;
      case PeriodicMethod::anderson: {
        if (mixed) {
          hist_g.clear();
          hist_f.clear();
        }
        hist_g.push_back(gx);
        hist_f.push_back(r.cwiseQuotient(scale_));
        if (static_cast<int>(hist_g.size()) > opt_.depth + 1) {
          hist_g.erase(hist_g.begin());
          hist_f.erase(hist_f.begin());
        }
        const int m = static_cast<int>(hist_g.size()) - 1;
        if (m == 0) {
          xn = gx;
          step = "fixed point";
          break;
        }
        Mat dF(N, m), dG(N, m);
        for (int k = 0; k < m; ++k) {
          dF.col(k) = hist_f[static_cast<std::size_t>(k + 1)] - hist_f[static_cast<std::size_t>(k)];
          dG.col(k) = hist_g[static_cast<std::size_t>(k + 1)] - hist_g[static_cast<std::size_t>(k)];
        }
        const Vec gamma = dF.colPivHouseholderQr().solve(hist_f.back());
        xn = gx - dG * gamma;
        step = "anderson (" + std::to_string(m) + " earlier)";
        break;
      }
      case PeriodicMethod::newton: {
        if (cycles_ + N >= opt_.max_cycles) {
          res.message = "a Newton iteration needs " + std::to_string(N) +
                        " more cycles (the monodromy by differences) than max cycles leaves";
          break;
        }
        const Mat Phi = monodromy_by_differences(res, x, gx);
        xn = x + (Mat::Identity(N, N) - Phi).colPivHouseholderQr().solve(r);
        step = "newton";
        break;
      }
      case PeriodicMethod::projected: {
        if (!have_lin) {
          build_projection(res);
          if (opt_.difference_jacobian && H_.size() > 0) {
            // H = L dG/dx V by one-sided differences along V's columns
            // (against G(x) at the tolerances the differences are taken at)
            const double rel = std::max(std::sqrt(set_.rtol), 1e-7);
            const Vec base = to_fine ? cycle(x, false) : gx;
            for (int k = 0; k < H_.cols(); ++k) {
              const Vec dir = V_.col(k);  // unit size in the scaled norm
              H_.col(k) = L_ * (cycle(x + rel * dir, false) - base) / rel;
            }
          }
          have_lin = true;
        } else if (opt_.secant && H_.size() > 0 && !mixed) {
          // (not across the change of tolerances: that difference is no slope)
          const Vec dz = L_ * (x - x_prev);
          const Vec dg = L_ * (gx - g_prev);
          const double dd = dz.squaredNorm();
          if (dd > 0.0) H_ += (dg - H_ * dz) * dz.transpose() / dd;
        }
        x_prev = x;
        g_prev = gx;
        const int pdim = static_cast<int>(H_.rows());
        if (pdim == 0) {
          xn = gx;
          step = "fixed point (no slow multiplier)";
          break;
        }
        const Vec z = L_ * r;
        const Mat I = Mat::Identity(pdim, pdim);
        // (I - H)^+ H z: directions whose multiplier is 1 to within 1e-3 (a
        // coordinate that the linearization leaves free, e.g. a
        // journal floating axially in its thrust bearing's gap) are left to
        // the fixed point
        Eigen::JacobiSVD<Mat> svd(I - H_, Eigen::ComputeFullU | Eigen::ComputeFullV);
        svd.setThreshold(1e-3);
        const Vec corr = svd.solve(H_ * z);
        xn = gx + V_ * corr;
        step = "projected newton (" + std::to_string(pdim) + " slow)";
        break;
      }
    }
    if (xn.size() == 0) break;  // the method cannot go on (message set)
    if (coarse_) step += " (coarse)";
    step += note;
    note.clear();
    mixed = to_fine;
    // A step that leaves the states the model takes (a journal outside its
    // clearance) is halved towards G(x), a state the integrator reached, up
    // to four times.
    Vec gn;
    bool failed = false;
    for (int half = 0;; ++half) {
      try {
        gn = cycle(xn, true);
        break;
      } catch (const Stopped&) {
        throw;
      } catch (const RunError& e) {
        if (half == 4 || xn == gx) {
          res.message = e.what();
          failed = true;
          break;
        }
        xn = gx + 0.5 * (xn - gx);
        step += ", halved";
      }
    }
    if (failed && opt_.method == PeriodicMethod::projected && !refined_ &&
        opt_.linearization != "averaged" && opt_.steps < static_cast<int>(lt_.size())) {
      // The step left the model's states even when halved: the stepped
      // linearization was too coarse for the scene (the rigid-ground engine
      // without its thrust bearing at 180 steps). Once more from the same
      // iterate with one implicit-Euler step per sample of the cycle.
      opt_.steps = static_cast<int>(lt_.size());
      refined_ = true;
      have_lin = false;
      res.message.clear();
      note = " (its linearization refined to " + std::to_string(opt_.steps) +
             " steps after a step that left the model's states)";
      continue;
    }
    if (failed) break;
    x = xn;
    gx = gn;
    update_scale();
    r = gx - x;
    record(res, step, r);
  }
  // without multipliers of its own, a method reports the linearization's
  if (res.multipliers.empty() && opt_.method != PeriodicMethod::newton && !st_.empty() &&
      p_.quasi_static().empty() && !p_.has_mass())
    linearized_multipliers(res, stepped_linearization(p_, t0_, T_, st_, sq_, sv_, opt_.steps));
  if (opt_.method == PeriodicMethod::projected && H_.size() > 0) {
    // the slow multipliers from the p x p Jacobian after its secant updates,
    // the others from the linearization
    Eigen::EigenSolver<Mat> es(H_);
    std::vector<FloquetMultiplier> slow;
    for (int k = 0; k < H_.rows(); ++k) {
      FloquetMultiplier f;
      f.mu = es.eigenvalues()[k];
      f.lives_in = lives_in((V_.cast<cd>() * es.eigenvectors().col(k)).eval());
      slow.push_back(f);
    }
    std::vector<FloquetMultiplier> rest;
    for (const FloquetMultiplier& f : res.multipliers)
      if (std::abs(f.mu) < opt_.slow) rest.push_back(f);
    res.multipliers = slow;
    res.multipliers.insert(res.multipliers.end(), rest.begin(), rest.end());
    std::sort(res.multipliers.begin(), res.multipliers.end(),
              [](const FloquetMultiplier& a, const FloquetMultiplier& b) {
                return std::abs(a.mu) > std::abs(b.mu);
              });
    if (res.multipliers.size() > 12) res.multipliers.resize(12);
    res.multiplier_source = std::string("the slow subspace's Jacobian") +
                            (opt_.secant ? " after its secant updates" : "") +
                            " (|mu| >= " + format_number(opt_.slow) +
                            "), the rest from the linearization over the first cycle";
  }
  if (!res.converged && res.message.empty()) {
    const PeriodicIteration& last = res.iterations.back();
    res.message = "no periodic solution within " + std::to_string(opt_.max_cycles) +
                  " cycles: the defect is " + format_number(last.defect) + " (tolerance " +
                  format_number(opt_.tol) + ") in " + last.worst;
    if (!res.multipliers.empty())
      res.message +=
          "; the slowest multiplier |mu| = " + format_number(std::abs(res.multipliers.front().mu)) +
          (res.multipliers.front().lives_in.empty()
               ? std::string()
               : " lives in " + res.multipliers.front().lives_in.front());
  }
  // newton's multipliers are the monodromy's, also when the start was periodic
  if (res.converged && (opt_.difference_floquet ||
                        (opt_.method == PeriodicMethod::newton && res.multipliers.empty())))
    monodromy_by_differences(res, x, gx);
  res.q = x.head(n_);
  res.v = x.tail(n_);
  res.sample_t = st_;
  res.sample_q = sq_;
  res.sample_v = sv_;
  res.cycles = cycles_;
  res.stats = stats_;
  res.wall = std::chrono::duration<double>(Clock::now() - clock0_).count();
  return res;
}

}  // namespace

const char* to_text(PeriodicMethod m) {
  switch (m) {
    case PeriodicMethod::projected:
      return "projected";
    case PeriodicMethod::newton:
      return "newton";
    case PeriodicMethod::anderson:
      return "anderson";
    case PeriodicMethod::fixed_point:
      return "fixed-point";
  }
  return "?";
}

PeriodicMethod periodic_method(const std::string& name) {
  for (PeriodicMethod m : {PeriodicMethod::projected, PeriodicMethod::newton,
                           PeriodicMethod::anderson, PeriodicMethod::fixed_point})
    if (name == to_text(m)) return m;
  throw InputError("--method: '" + name +
                   "' is not a periodic method (projected, newton, anderson, fixed-point)");
}

namespace {

// The multipliers and eigenvectors of lin.Phi.
void decompose(Linearization& lin) {
  Eigen::EigenSolver<Mat> es(lin.Phi);
  if (es.info() != Eigen::Success)
    throw RunError("the eigenvalues of the linearized monodromy did not converge");
  lin.X = es.eigenvectors();
  lin.mu.clear();
  for (int k = 0; k < es.eigenvalues().size(); ++k) lin.mu.push_back(es.eigenvalues()[k]);
}

}  // namespace

Linearization averaged_linearization(Problem& p, double T, const std::vector<double>& t,
                                     const std::vector<Vec>& q, const std::vector<Vec>& v) {
  const int n = p.size();
  SpMat K = p.jacobian_pattern(), C = p.jacobian_pattern();
  Mat Ks = Mat::Zero(n, n), Cs = Mat::Zero(n, n);
  const std::size_t count = t.size();
  if (count == 0) throw std::logic_error("averaged_linearization: no state");
  // at most 24 states, spread over those given
  const std::size_t use = std::min<std::size_t>(count, 24);
  for (std::size_t k = 0; k < use; ++k) {
    const std::size_t j = k * count / use;
    p.force_jacobian(t[j], q[j].data(), v[j].data(), K, C);
    Ks += Mat(K);
    Cs += Mat(C);
  }
  Ks /= static_cast<double>(use);
  Cs /= static_cast<double>(use);
  Mat A = Mat::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n) = Mat::Identity(n, n);
  A.bottomLeftCorner(n, n) = -Ks;
  A.bottomRightCorner(n, n) = -Cs;
  Eigen::EigenSolver<Mat> es(A);
  if (es.info() != Eigen::Success)
    throw RunError("the eigenvalues of the averaged linearization did not converge");
  Linearization lin;
  lin.X = es.eigenvectors();
  Eigen::VectorXcd mu(2 * n);
  for (int k = 0; k < 2 * n; ++k) {
    mu[k] = std::exp(es.eigenvalues()[k] * T);
    lin.mu.push_back(mu[k]);
  }
  lin.Phi = (lin.X * mu.asDiagonal() * lin.X.inverse()).real();
  lin.source = "exp(A T) of the linearization averaged over the first cycle";
  return lin;
}

Linearization stepped_linearization(Problem& p, double t0, double T, const std::vector<double>& t,
                                    const std::vector<Vec>& q, const std::vector<Vec>& v,
                                    int steps) {
  const int n = p.size();
  if (t.empty()) throw std::logic_error("stepped_linearization: no state");
  const int stride = std::max(
      1, static_cast<int>(std::lround(static_cast<double>(t.size()) / std::max(steps, 1))));
  std::vector<std::size_t> at;
  for (std::size_t k = 0; k < t.size(); k += static_cast<std::size_t>(stride)) at.push_back(k);
  SpMat K = p.jacobian_pattern(), C = p.jacobian_pattern();
  Mat Pq = Mat::Zero(n, 2 * n), Pv = Mat::Zero(n, 2 * n);  // Phi = [Pq; Pv]
  Pq.leftCols(n).setIdentity();
  Pv.rightCols(n).setIdentity();
  double tk = t0;
  for (std::size_t s = 0; s < at.size(); ++s) {
    // the step from tk to the next sample (the cycle's end after the last),
    // its matrix at the state of the step's end (the first state for the end)
    const bool last = s + 1 == at.size();
    const std::size_t j = last ? at.front() : at[s + 1];
    const double t1 = last ? t0 + T : t[j];
    const double h = t1 - tk;
    if (!(h > 0.0)) continue;
    p.force_jacobian(last ? t0 + T : t[j], q[j].data(), v[j].data(), K, C);
    // (I - h A) [q1; v1] = [q; v]:  q1 = q + h v1,  (I + h C + h^2 K) v1 = v - h K q
    const Mat Kd(K), Cd(C);
    Mat S = h * Cd + h * h * Kd;
    S.diagonal().array() += 1.0;
    const Mat Vn = S.partialPivLu().solve(Pv - h * Kd * Pq);
    Pq += h * Vn;
    Pv = Vn;
    tk = t1;
  }
  Linearization lin;
  lin.Phi.resize(2 * n, 2 * n);
  lin.Phi << Pq, Pv;
  decompose(lin);
  lin.source = "the linearized equations stepped over the first cycle (implicit Euler, " +
               std::to_string(at.size()) + " steps)";
  return lin;
}

PeriodicResult find_periodic(Problem& p, double t0, double T, const Vec& q0, const Vec& v0,
                             const IntegratorSettings& settings, const PeriodicOptions& opt,
                             std::vector<double> samples, CycleObserver* observer) {
  if (!(T > 0.0) || !std::isfinite(T)) throw InputError("the period must be a positive time");
  Solver s(p, t0, T, settings, opt, std::move(samples), observer);
  return s.solve(q0, v0);
}

}  // namespace evas::run
