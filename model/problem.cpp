#include "model/problem.h"

#include <sstream>

namespace evas {

namespace {
const SpMat& empty_pattern() {
  static const SpMat empty;
  return empty;
}
}  // namespace

void Problem::force_jacobian_combination(double t, const double* q, const double* v, double ck,
                                         double cc, SpMat& S) {
  if (comb_K_.nonZeros() != S.nonZeros()) {  // (allocates on the first call only)
    comb_K_ = jacobian_pattern();
    comb_C_ = comb_K_;
  }
  force_jacobian(t, q, v, comb_K_, comb_C_);
  Eigen::Map<Vec>(S.valuePtr(), S.nonZeros()) =
      ck * Eigen::Map<const Vec>(comb_K_.valuePtr(), S.nonZeros()) +
      cc * Eigen::Map<const Vec>(comb_C_.valuePtr(), S.nonZeros());
}

void Problem::mass(double, const double*, SpMat&) {
  throw RunError("problem has no mass matrix (has_mass() is false)");
}
const SpMat& Problem::mass_pattern() const { return empty_pattern(); }
void Problem::constraint(double, const double*, const double*, double*, double*, double*) {
  throw RunError("problem has no constraints");
}
void Problem::constraint_jacobian(double, const double*, SpMat&) {
  throw RunError("problem has no constraints");
}
const SpMat& Problem::constraint_pattern() const { return empty_pattern(); }
std::string Problem::constraint_name(int i) const { return "g" + std::to_string(i + 1); }

bool Problem::internal_algebraic(int) const { throw RunError("problem has no internal states"); }
void Problem::internal_initial(double, const Vec&, const Vec&, Vec& z) { z.resize(0); }
void Problem::set_internal(const double*) {}
void Problem::internal_rate(double, const double*, const double*, double*) {
  throw RunError("problem has no internal states");
}
void Problem::internal_jacobian(double, const double*, const double*, SpMat&, SpMat&, SpMat&,
                                SpMat&) {
  throw RunError("problem has no internal states");
}
void Problem::internal_patterns(SpMat& Fz, SpMat& Hq, SpMat& Hv, SpMat& Hz) const {
  Fz.resize(size(), 0);
  Hq.resize(0, size());
  Hv.resize(0, size());
  Hz.resize(0, 0);
}
std::string Problem::internal_name(int i) const { return "internal state " + std::to_string(i); }

const std::vector<int>& Problem::quasi_static() const {
  static const std::vector<int> none;
  return none;
}

std::string Problem::describe_coordinate(int i) const { return "coordinate " + std::to_string(i); }

std::string Problem::describe_state(double t, const double* q, const double* v) const {
  std::ostringstream os;
  os << "t = " << t << " s, n = " << size();
  double mq = 0.0, mv = 0.0;
  for (int i = 0; i < size(); ++i) {
    mq = std::max(mq, std::abs(q[i]));
    mv = std::max(mv, std::abs(v[i]));
  }
  os << ", max|q| = " << mq << ", max|v| = " << mv;
  return os.str();
}

void start_internal_states(Problem& p, double t, const Vec& q, const Vec& v) {
  if (p.internal_count() == 0) return;
  Vec z;
  p.internal_initial(t, q, v, z);
  p.set_internal(z.data());
}

}  // namespace evas
