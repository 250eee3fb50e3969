// The transistor amplifier of the Test Set for IVP Solvers (F. Mazzia, C.
// Magherini, University of Bari, release 2.4, 2008; problem "transamp", after
// E. Hairer, C. Lubich, M. Roche, The Numerical Solution of Differential-
// Algebraic Systems by Runge-Kutta Methods, Springer LNM 1409, 1989): the node
// voltages of a two-stage amplifier, an index-1 DAE M y' = f(t, y) of 8
// unknowns with a singular (rank 5), non-diagonal M of the capacitors,
//     M = [-C1  C1                         ]
//         [ C1 -C1                         ]
//         [        -C2                     ]
//         [            -C3  C3             ]
//         [             C3 -C3             ]
//         [                    -C4         ]
//         [                        -C5  C5 ]
//         [                         C5 -C5 ],
// f1 = (y1 - Ue(t)) / R0,                f2 = y2 / R1 + (y2 - Ub) / R2 + (1 - a) g(y2 - y3),
// f3 = y3 / R3 - g(y2 - y3),            f4 = (y4 - Ub) / R4 + a g(y2 - y3),
// f5 = y5 / R5 + (y5 - Ub) / R6 + (1 - a) g(y5 - y6),
// f6 = y6 / R7 - g(y5 - y6),            f7 = (y7 - Ub) / R8 + a g(y5 - y6),
// f8 = y8 / R9,
// with g(x) = b (exp(x / UF) - 1), Ue(t) = 0.1 sin(200 pi t), Ub = 6,
// UF = 0.026, a = 0.99, b = 1e-6, R0 = 1000, R1 ... R9 = 9000, Ck = k 1e-6.
// t in [0, 0.2]; y(0) and y'(0) are the test set's (y'(0) to its 9 digits).
#pragma once

#include "model/implicit_dae.h"

namespace evas::problems {

class Transistor final : public ImplicitDae {
 public:
  int size() const override { return 8; }
  Mat mass() const override;
  void rhs(double t, const double* y, double* f) override;
  void rhs_jacobian(double t, const double* y, Mat& J) override;
  void initial(Vec& y, Vec& yp) const override;
  std::string component_name(int i) const override;
};

}  // namespace evas::problems
