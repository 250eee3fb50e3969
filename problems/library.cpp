#include "problems/library.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "problems/akzo.h"
#include "problems/andrews.h"
#include "problems/car_axis.h"
#include "problems/fekete.h"
#include "problems/pendulum.h"
#include "problems/slider_crank.h"
#include "problems/transistor.h"
#include "problems/wheelset.h"

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
  {
    LibraryProblem p;
    p.name = "fekete";
    p.description =
        "Fekete's problem: 20 points on the unit sphere, 60 positions, 20 constraints, "
        "index 3 (the test set's GGL form is evas's ggl), t in [0, 1000] (IVP Test Set)";
    p.t_end = 1000.0;
    // IVP Test Set, problem fekete, RADAU5 at rtol = atol = 1e-12: p, then p'
    p.reference_qv = {-0.4070263380333202e+00, 0.3463758772791802e+00,  0.8451942450030429e+00,
                      0.7752934752521549e-01,  -0.2628662719972299e+00, 0.9617122871829146e+00,
                      0.7100577833343567e+00,  0.1212948055586120e+00,  0.6936177005172217e+00,
                      0.2348267744557627e+00,  0.7449277976923311e+00,  0.6244509285956391e+00,
                      -0.4341114738782885e+00, 0.8785430442262876e+00,  0.1992720444237660e+00,
                      -0.9515059600312596e+00, 0.2203508762787005e+00,  0.2146669498274008e+00,
                      -0.6385191643609878e+00, -0.4310833259390688e+00, 0.6375425027722121e+00,
                      -0.1464175087914336e+00, -0.9380871635228862e+00, 0.3139337298744690e+00,
                      0.5666974065069942e+00,  -0.6739221885076542e+00, 0.4740073135462156e+00,
                      0.9843259538440293e+00,  -0.1696995357819996e+00, -0.4800504290609090e-01,
                      0.1464175087914331e+00,  0.9380871635228875e+00,  -0.3139337298744656e+00,
                      -0.7092757549979014e+00, 0.5264062637139616e+00,  -0.4688542938854929e+00,
                      -0.8665731819284478e+00, -0.4813878059756024e+00, -0.1315929352982178e+00,
                      -0.2347897778700538e+00, -0.8594340408013130e+00, -0.4541441287957579e+00,
                      0.5530976940074118e+00,  -0.7674370265615124e+00, -0.3242273140037833e+00,
                      0.7711050969896927e+00,  0.6357041816577034e+00,  0.3573685519777001e-01,
                      0.7103951209379591e+00,  0.2403570431280519e+00,  -0.6614886725910596e+00,
                      -0.3038208738735660e-01, 0.4501923293640461e+00,  -0.8924145871442046e+00,
                      -0.5772996158107093e+00, -0.1766763414971813e+00, -0.7971892020969544e+00,
                      0.2414481766969039e+00,  -0.3416456818373135e+00, -0.9082846503446250e+00,
                      0.2409619682166627e-15,  -0.1139818460497816e-15, 0.1627536276556335e-15,
                      0.1745651819597609e-15,  -0.1914278710633076e-15, -0.6639600671806291e-16,
                      0.1708576733899083e-15,  -0.2277602521390053e-15, -0.1350782790950654e-15,
                      0.2411941341109454e-15,  -0.1438238671800488e-15, 0.8087033550666644e-16,
                      0.1618239105233347e-15,  0.1837556152070701e-16,  0.2715177369929503e-15,
                      0.7930078658689191e-16,  0.7482020588342764e-16,  0.2746974939098084e-15,
                      0.8849338913035911e-16,  -0.5940734725324115e-16, 0.4845984056889910e-16,
                      -0.3728835248155620e-16, -0.4600332954062859e-16, -0.1548568884846698e-15,
                      0.2507541692375411e-16,  -0.1560155223230823e-15, -0.2517946296860555e-15,
                      -0.3739779361502470e-16, -0.1381663620885020e-15, -0.2784051540342329e-15,
                      0.6624397102887671e-16,  0.4226207488883120e-16,  0.1571821772296610e-15,
                      -0.4112243677286995e-16, 0.1939960344265876e-15,  0.2800184977692136e-15,
                      -0.9189023375328813e-16, 0.1392943179389155e-15,  0.9556003995587458e-16,
                      -0.2234188557495892e-15, 0.1276804778190781e-15,  -0.1261196211463950e-15,
                      -0.1887754149742397e-15, -0.2140788698695373e-16, -0.2713591291421657e-15,
                      0.1107887633060814e-15,  -0.1318443715631340e-15, -0.4521275683078691e-16,
                      -0.1277688851278605e-15, 0.4850914012115388e-16,  -0.1195891666741192e-15,
                      -0.1569641653843750e-15, 0.1856239009452638e-15,  0.9898466095646496e-16,
                      -0.2068030800303723e-15, 0.2451470336752085e-15,  0.9542986459336358e-16,
                      -0.2456074075580993e-15, 0.1532475480661800e-15,  -0.1229326332276474e-15};
    // the test set's lambda with evas's sign (+ G^T lambda on the left)
    p.reference_lambda = {0.4750000000000000e+01, 0.4750000000000001e+01, 0.4750000000000000e+01,
                          0.4750000000000000e+01, 0.4750000000000000e+01, 0.4750000000000000e+01,
                          0.4750000000000000e+01, 0.4750000000000000e+01, 0.4750000000000000e+01,
                          0.4750000000000000e+01, 0.4750000000000001e+01, 0.4750000000000001e+01,
                          0.4750000000000000e+01, 0.4750000000000000e+01, 0.4750000000000000e+01,
                          0.4750000000000000e+01, 0.4749999999999999e+01, 0.4750000000000000e+01,
                          0.4750000000000000e+01, 0.4750000000000000e+01};
    p.source =
        "IVP Test Set (Mazzia & Magherini, Bari), problem fekete, RADAU5 rtol = atol = 1e-12";
    p.make = [] { return std::make_unique<Fekete>(); };
    v.push_back(std::move(p));
  }
  {
    LibraryProblem p;
    p.name = "crank";
    p.description =
        "flexible slider crank: crank, elastic rod (4 coordinates), slider; 7 coordinates, 3 "
        "constraints, index 3 (the test set's index-2 form is evas's index-2), M(p), "
        "t in [0, 0.1] (IVP Test Set; Simeon 1996)";
    p.t_end = 0.1;
    // IVP Test Set, problem crank, MEBDFI at rtol = atol = 1e-14: p, then p'
    p.reference_qv = {0.1500000000000104e+2,  -0.3311734988256260,    0.1697373328427860,
                      0.1893192899613509e-3,  0.2375751249879174e-4,  -0.5323896770569702e-5,
                      -0.8363313279112129e-5, 0.1500000000000000e+3,  0.6025346755138369e+2,
                      -0.8753116326670527e+1, -0.3005541400289738e-1, -0.5500431812571696e-2,
                      0.4974111734266989e-3,  0.1105560003626645e-2};
    p.reference_lambda = {-0.6232935833287916e+2, -0.1637920993367306e+3, 0.2529857947066878e+2};
    p.source =
        "IVP Test Set (Mazzia & Magherini, Bari), problem crank, MEBDFI at rtol = atol = "
        "1e-14";
    p.make = [] { return std::make_unique<SliderCrank>(); };
    v.push_back(std::move(p));
  }
  {
    LibraryProblem p;
    p.name = "chemakzo";
    p.description =
        "chemical Akzo Nobel problem: 6 concentrations, M y' = f with one algebraic "
        "equation, index 1, t in [0, 180] (IVP Test Set)";
    p.t_end = 180.0;
    p.reference_y = {0.1150794920661702,    0.1203831471567715e-2, 0.1611562887407974,
                     0.3656156421249283e-3, 0.1708010885264404e-1, 0.4873531310307455e-2};
    p.source = "IVP Test Set (Mazzia & Magherini, Bari), problem chemakzo, its reference solution";
    p.make_implicit = [] { return std::make_unique<Akzo>(); };
    v.push_back(std::move(p));
  }
  {
    LibraryProblem p;
    p.name = "transamp";
    p.description =
        "transistor amplifier: 8 node voltages, M y' = f with a singular M (rank 5), index 1, "
        "stiff, t in [0, 0.2] (IVP Test Set; Hairer, Lubich & Roche 1989)";
    p.t_end = 0.2;
    p.reference_y = {-0.5562145012262709e-2, 0.3006522471903042e+1, 0.2849958788608128e+1,
                     0.2926422536206241e+1,  0.2704617865010554e+1, 0.2761837778393145e+1,
                     0.4770927631616772e+1,  0.1236995868091548e+1};
    p.source =
        "IVP Test Set (Mazzia & Magherini, Bari), problem transamp, PSIDE at rtol = atol "
        "= 1e-14";
    p.make_implicit = [] { return std::make_unique<Transistor>(); };
    v.push_back(std::move(p));
  }
  {
    LibraryProblem p;
    p.name = "wheelset";
    p.description =
        "railway wheelset on a straight track (hunting, creep forces): 17 unknowns, index 2, "
        "M(phi) y' = f made constant-mass, t in [0, 10] (IVP Test Set; Simeon, Fuehrer & "
        "Rentrop 1991)";
    p.t_end = 10.0;
    // x, y, z, theta, phi, their velocities, beta', psi_R, xi_R, psi_L, xi_L,
    // the multipliers / 1e4 (the test set's order of its 17 unknowns)
    p.reference_y = {0.86355386965811e-02,  0.13038281022727e-04,  -0.93635784016818e-04,
                     -0.13642299804033e-01, 0.15292895005422e-02,  -0.76985374142666e-01,
                     -0.25151106429207e-03, 0.20541188079539e-02,  -0.23904837703692e+00,
                     -0.13633468454173e-01, -0.24421377661131e+00, -0.33666751972196e-03,
                     -0.15949425684022e+00, 0.37839614386969e-03,  0.14173214964613e+00,
                     -0.10124044903201e-01, -0.56285630573753e-02};
    p.source =
        "IVP Test Set (Mazzia & Magherini, Bari), problem wheelset, DASSL at rtol = atol = "
        "1e-9 (multipliers out of the error control)";
    p.make_implicit = [] { return std::make_unique<Wheelset>(); };
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

namespace {

// mescd and scd of y against ref over their common components
Score score_values(const std::vector<double>& ref, const Vec& y, double ratio) {
  Score s;
  double mixed = 0.0, rel = 0.0, big = 0.0;
  for (double r : ref) big = std::max(big, std::abs(r));
  const auto n = std::min(ref.size(), static_cast<std::size_t>(y.size()));
  for (std::size_t i = 0; i < n; ++i) {
    const double yi = y(static_cast<Eigen::Index>(i)), r = ref[i];
    const double em = std::abs(yi - r) / (ratio + std::abs(r));
    if (!(em <= mixed)) s.worst = static_cast<int>(i);  // NaN counts as the worst
    mixed = std::isnan(em) ? std::numeric_limits<double>::infinity() : std::max(mixed, em);
    // relative digits only where the reference is not (nearly) zero
    if (std::abs(r) > 1e-6 * big) rel = std::max(rel, std::abs(yi - r) / std::abs(r));
  }
  s.mescd = digits(mixed);
  s.scd = digits(rel);
  s.mescd_lambda = std::numeric_limits<double>::quiet_NaN();
  return s;
}

}  // namespace

Score score_implicit(const LibraryProblem& p, const Vec& y, double rtol, double atol) {
  return score_values(p.reference_y, y, atol / rtol);
}

Score score(const LibraryProblem& p, const Vec& q, const Vec& v, const Vec& lambda, double rtol,
            double atol) {
  const double ratio = atol / rtol;
  Vec qv(q.size() + v.size());
  qv << q, v;
  Score s = score_values(p.reference_qv, qv, ratio);
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
