#include "problems/library.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "problems/andrews.h"
#include "problems/car_axis.h"
#include "problems/pendulum.h"

namespace evas::problems {

namespace {

std::vector<LibraryProblem> build() {
  std::vector<LibraryProblem> v;
  {
    LibraryProblem p;
    p.name = "andrews";
    p.description =
        "Andrews' squeezing mechanism: 7 bodies, 7 angles, 6 constraints, index 3, M(q), "
        "t in [0, 0.03] (IVP Test Set; Hairer & Wanner 1996, VII.7)";
    p.t_end = 0.03;
    // IVP Test Set, reference by PSIDE at tol 1e-14: positions, velocities
    p.reference_qv = {15.81077119629904,  -15.75637105984298, .4082224013073101e-1,
                      -.5347301163226948, .5244099658805304,  .5347301163226948,
                      1.048080741042263,  1139.920302151208,  -1424.379294994111,
                      11.03291221937134,  19.29337464421385,  .5735699284790808,
                      -19.29337464421385, .3231791658026955};
    p.source = "IVP Test Set (Mazzia & Magherini, Bari), problem andrews, PSIDE tol 1e-14";
    p.make = [] { return std::make_unique<Andrews>(); };
    v.push_back(std::move(p));
  }
  {
    LibraryProblem p;
    p.name = "car-axis";
    p.description =
        "car axis: 4 positions, 2 constraints, index 3, time-dependent constraint, "
        "t in [0, 3] (IVP Test Set)";
    p.t_end = 3.0;
    p.reference_qv = {.493455784275402809122e-1,  .496989460230171153861,
                      1.04174252488542151681,     .373911027265361256927,
                      -.770583684040972357970e-1, .744686658723778553466e-2,
                      .175568157537232222276e-1,  .770341043779251976443};
    // the test set's multipliers with evas's sign (+ G^T lambda on the left)
    p.reference_lambda = {.473688659084893324729e-2, .110468033125734368808e-2};
    p.source = "IVP Test Set (Mazzia & Magherini, Bari), problem caraxis, its reference solution";
    p.make = [] { return std::make_unique<CarAxis>(); };
    v.push_back(std::move(p));
  }
  {
    LibraryProblem p;
    p.name = "pendulum";
    p.description =
        "planar pendulum in Cartesian coordinates, m = 2, L = 1, released at 1 rad, "
        "one period, index 3 (Hairer & Wanner 1996, VII.1)";
    Pendulum pend(2.0, 1.0, 9.81, 1.0);
    p.t_end = pend.period();
    Vec q, vv;
    double lam = 0.0;
    pend.exact(p.t_end, q, vv, lam);
    p.reference_qv = {q(0), q(1), vv(0), vv(1)};
    p.reference_lambda = {lam};
    p.source = "exact: Jacobi elliptic functions (Lawden 1989), boost::math";
    p.make = [] { return std::make_unique<Pendulum>(2.0, 1.0, 9.81, 1.0); };
    v.push_back(std::move(p));
  }
  return v;
}

double digits(double worst) {
  return worst > 0.0 ? -std::log10(worst) : std::numeric_limits<double>::infinity();
}

}  // namespace

const std::vector<LibraryProblem>& library() {
  static const std::vector<LibraryProblem> lib = build();
  return lib;
}

const LibraryProblem& library_problem(const std::string& name) {
  std::string names;
  for (const auto& p : library()) {
    if (p.name == name) return p;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw InputError("no problem named '" + name + "' (known: " + names + ")");
}

Score score(const LibraryProblem& p, const Vec& q, const Vec& v, const Vec& lambda, double rtol,
            double atol) {
  const double ratio = atol / rtol;
  const int n = static_cast<int>(q.size());
  Score s;
  double mixed = 0.0, rel = 0.0, big = 0.0;
  for (double r : p.reference_qv) big = std::max(big, std::abs(r));
  for (int i = 0; i < 2 * n && i < static_cast<int>(p.reference_qv.size()); ++i) {
    const double y = i < n ? q(i) : v(i - n), r = p.reference_qv[static_cast<std::size_t>(i)];
    const double em = std::abs(y - r) / (ratio + std::abs(r));
    if (!(em <= mixed)) s.worst = i;  // NaN counts as the worst
    mixed = std::isnan(em) ? std::numeric_limits<double>::infinity() : std::max(mixed, em);
    // relative digits only where the reference is not (nearly) zero
    if (std::abs(r) > 1e-6 * big) rel = std::max(rel, std::abs(y - r) / std::abs(r));
  }
  s.mescd = digits(mixed);
  s.scd = digits(rel);
  s.mescd_lambda = std::numeric_limits<double>::quiet_NaN();
  if (!p.reference_lambda.empty() &&
      lambda.size() == static_cast<Eigen::Index>(p.reference_lambda.size())) {
    double ml = 0.0;
    for (std::size_t k = 0; k < p.reference_lambda.size(); ++k) {
      const double r = p.reference_lambda[k];
      ml = std::max(ml, std::abs(lambda(static_cast<Eigen::Index>(k)) - r) / (ratio + std::abs(r)));
    }
    s.mescd_lambda = digits(ml);
  }
  return s;
}

}  // namespace evas::problems
