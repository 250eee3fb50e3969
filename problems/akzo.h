// The chemical Akzo Nobel problem of the Test Set for IVP Solvers (F. Mazzia,
// C. Magherini, University of Bari, release 2.4, 2008; problem "chemakzo",
// contributed by Akzo Nobel Central Research): the reaction of FLB and ZHU in
// a stirred vessel with CO2 bubbled through it, an index-1 DAE of 6 unknowns,
//     M y' = f(y),   M = diag(1, 1, 1, 1, 1, 0),   t in [0, 180],
// with the reaction rates (k1 = 18.7, k2 = 0.58, k3 = 0.09, k4 = 0.42,
// K = 34.4, klA = 3.3, Ks = 115.83, pCO2 = 0.9, H = 737)
//     r1 = k1 y1^4 sqrt(y2),  r2 = k2 y3 y4,  r3 = k2 / K y1 y5,
//     r4 = k3 y1 y4^2,        r5 = k4 y6^2 sqrt(y2),
//     Fin = klA (pCO2 / H - y2),
// and
//     f1 = -2 r1 + r2 - r3 - r4,        f2 = -r1 / 2 - r4 - r5 / 2 + Fin,
//     f3 = r1 - r2 + r3,                f4 = -r2 + r3 - 2 r4,
//     f5 = r2 - r3 + r5,                f6 = Ks y1 y4 - y6.
// y(0) = (0.444, 0.00123, 0, 0.007, 0, Ks 0.444 0.007), y'(0) = f(y(0)) in
// the first five components and Ks (y1' y4 + y1 y4') in the sixth.
#pragma once

#include "model/implicit_dae.h"

namespace evas::problems {

class Akzo final : public ImplicitDae {
 public:
  int size() const override { return 6; }
  Mat mass() const override;
  void rhs(double t, const double* y, double* f) override;
  void rhs_jacobian(double t, const double* y, Mat& J) override;
  void initial(Vec& y, Vec& yp) const override;
  std::string component_name(int i) const override;
};

}  // namespace evas::problems
