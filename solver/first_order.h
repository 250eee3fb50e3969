// First-order views of a second-order Problem, with y = [q; v] (2n):
//   implicit residual (IDA):  F(t, y, yd) = [ yd_q - v ; yd_v + f(t, q, v) ]
//       iteration matrix      J = dF/dy + cj dF/dyd = [ cj I , -I ; K , C + cj I ]
//   explicit form (CVODE):    yd = g(t, y) = [ v ; -f(t, q, v) ]
//       Jacobian              dg/dy = [ 0 , I ; -K , -C ]
// Both matrices have patterns fixed at construction (CSC, int indices);
// filling them allocates nothing.
//
// Internal states z (Problem::internal_count(), differential only; an
// algebraic one is refused here, as neither explicit form has a place for it):
// y = [q; v; z], residual rows z' - h(t, q, v, z), rhs rows h, Jacobian blocks
// Fz = df/dz in (v, z), Hq, Hv, Hz in (z, q), (z, v), (z, z), with signs as for
// K and C. The problem's current z is set from y before every evaluation.
//
// Quasi-static coordinates (Problem::quasi_static) have no yd_v term: their
// rows are f_i = 0 and their (v, v) entry is C_ii alone (the mass diagonal m
// of solver/quasi_static.h). The implicit residual takes them; the explicit
// form cannot (rhs() and rhs_jacobian() throw std::logic_error).
#pragma once

#include <vector>

#include "dae/internal_blocks.h"
#include "model/problem.h"

namespace evas {

class FirstOrderForm {
 public:
  explicit FirstOrderForm(Problem& p);

  Problem& problem() { return p_; }
  int size() const { return 2 * n_ + nz_; }
  /// Number of internal states (after q and v in y).
  int internal_count() const { return nz_; }

  void residual(double t, const double* y, const double* yd, double* F);
  void residual_jacobian(double t, const double* y, double cj, SpMat& J);
  const SpMat& residual_pattern() const { return Jres_; }

  void rhs(double t, const double* y, double* yd);
  void rhs_jacobian(double t, const double* y, SpMat& J);
  const SpMat& rhs_pattern() const { return Jrhs_; }

 private:
  Problem& p_;
  int n_, nz_;
  SpMat K_, C_;
  Vec m_;  // diag(M): 0 for quasi-static coordinates, else 1
  bool unit_mass_ = true;
  dae::InternalBlocks zb_;  // internal states (same positions in both matrices)
  std::vector<int> pZZ_;    // their (z, z) diagonal
  SpMat Jres_, Jrhs_;
  // value positions in Jres_/Jrhs_ of: the K and C entries (by K_'s value index),
  // the cj diagonal entries, and the +-I entries.
  std::vector<int> res_K_, res_C_, res_cjq_, res_cjv_, res_I_;
  std::vector<int> rhs_K_, rhs_C_, rhs_I_;
};

}  // namespace evas
