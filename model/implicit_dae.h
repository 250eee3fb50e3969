// A first-order implicit DAE with a constant (possibly singular) mass matrix,
//     M y' = f(t, y),   y(0) = y0,  y'(0) = yp0 (consistent),
// the form of the chemical and electrical problems of the Test Set for IVP
// Solvers (F. Mazzia, C. Magherini, University of Bari, release 2.4, 2008)
// and of RADAU5's input (E. Hairer, G. Wanner, Solving Ordinary Differential
// Equations II, 2nd ed., Springer 1996, section IV.8 and VI.6). The mechanical
// problems of evas (model/problem.h) are second-order and have their own
// interface; this one serves problems that are first-order by nature.
//
// The index of each component (1, 2 or 3) is what an error estimate scales by:
// a component of index k has its local error measured after multiplication by
// h^(k-1) (Hairer & Wanner 1996, VII.8; RADAU5's NIND1, NIND2, NIND3), and an
// integrator may leave components of index > 1 out of its error test.
#pragma once

#include <string>

#include "model/types.h"

namespace evas {

class ImplicitDae {
 public:
  virtual ~ImplicitDae() = default;
  virtual int size() const = 0;
  /// The constant mass matrix M (size x size).
  virtual Mat mass() const = 0;
  /// f(t, y).
  virtual void rhs(double t, const double* y, double* f) = 0;
  /// J = df/dy at (t, y), all size x size entries written.
  virtual void rhs_jacobian(double t, const double* y, Mat& J) = 0;
  /// Consistent initial values y0 and y'0 at t = 0.
  virtual void initial(Vec& y, Vec& yp) const = 0;
  /// Index of component i (1 for a differential or index-1 algebraic one).
  virtual int component_index(int i) const {
    (void)i;
    return 1;
  }
  /// What component i is, for messages and tables (e.g. "y3 (node 3 voltage)").
  virtual std::string component_name(int i) const { return "y" + std::to_string(i + 1); }

  /// f(t, y) into a vector (for tests and tables).
  void f_at(double t, const Vec& y, Vec& f) {
    f.resize(size());
    rhs(t, y.data(), f.data());
  }

  long rhs_evals = 0, jacobian_evals = 0;
};

}  // namespace evas
