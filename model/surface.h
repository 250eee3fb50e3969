// Surface velocity and equivalent radiated power (ERP) of a node set of an
// elastic body (docs/theory.md section 8.3).
//
// A surface set carries, per node i, the area A_i it stands for [m^2] and its
// outward unit normal n_i in the body's LOF axes (from the FE mesh's faces,
// io/calculix.h mesh_surfaces, or given in the scene). The normal velocity in
// the ground frame, in LOF axes, of node i at undeformed position s_i is
//   v_n,i = n_i . (R^T v_o + w_L x s_i + Phi_i qdot) = b_i . u,
//   u = [R^T v_o; w_L; qdot],  b_i = [n_i; s_i x n_i; Phi_i^T n_i]
// (R, v_o the LOF's rotation and origin velocity, w_L = R^T w its angular
// velocity in LOF axes). It leaves out w_L x (Phi_i q), the turn of the
// deflection with the frame: exact for a body whose LOF does not rotate (the
// cylinder block), second order (deflection times frame speed) otherwise.
//
// Radiated power is approximated by the equivalent radiated power (Fritze,
// Marburg & Hardtke 2009, "Estimation of radiated sound power: a case study on
// common approximation methods", Acta Acustica u. Acustica 95, 833-842):
// every surface element radiates as a plane wave, sigma = 1,
//   ERP(t) = rho c sum_i A_i v_n,i(t)^2 = rho c u^T G u,  G = sum_i A_i b_i b_i^T,
// whose time mean is the ERP of the run (1/2 rho c sum A_i |v_hat_i|^2 for
// harmonic motion of amplitude v_hat). The K x K matrix G (K = 6 + modes) is
// formed once ("invariant form"): a sample costs O(K^2), not O(nodes K). With
// G = E diag(lambda) E^T, the components c_k = sqrt(rho c lambda_k) e_k^T u
// [W^0.5] give ERP = sum_k c_k^2 and, being linear in u, the ERP spectrum
// ERP(f) = sum_k (power of c_k at f) (post/erp_spectrum.h).
//
// Rigid and elastic parts. u splits into the body's rigid-body velocity u_r
// (the LOF's v_o and w_L, and the coordinates of the body's explicit rigid
// modes, ModeKind::Rigid) and its elastic velocity u_e (every other modal
// coordinate), u = u_r + u_e. ERP_rigid = rho c u_r^T G u_r is what the
// surface would "radiate" moving as a rigid body (an engine rocking on its
// mounts), ERP_elastic = rho c u_e^T G u_e what its deformation radiates; the
// two do not sum to ERP (the cross term 2 rho c u_r^T G u_e, which averages out
// over a cycle only when the two parts are uncorrelated). A rigid body moving
// on its mounts has u_e = 0 and so no elastic ERP. The elastic part has its
// own components e_k = sqrt(rho c mu_k) f_k^T u (G_e = sum_i A_i b_e,i b_e,i^T
// = F diag(mu) F^T, b_e,i = b_i with the rigid entries zeroed), so that its
// spectrum is formed as the total's is.
#pragma once

#include <string>
#include <vector>

#include "model/types.h"

namespace evas {

/// Per-node areas and outward normals of a surface node set.
struct SurfaceSet {
  std::vector<long> nodes;                          ///< FE node ids
  Vec area;                                         ///< [m^2] per node
  Eigen::Matrix<double, Eigen::Dynamic, 3> normal;  ///< unit outward normals (LOF axes)

  double total_area() const { return area.sum(); }
  /// Throws InputError(`who` ...) for mismatched sizes, a negative or
  /// non-finite area, no area at all, or a normal that is not a unit vector.
  void validate(const std::string& who) const;
};

struct ModalBody;
struct LofState;

/// The set's normal velocity and ERP from a body's motion (see above).
class SurfaceRadiation {
 public:
  /// `rho_c` [kg/(m^2 s)] (air at 20 C: 413). `per_node`: also the normal
  /// velocity of every node. Throws InputError naming `who` when a node is
  /// not in the body.
  SurfaceRadiation(const ModalBody& body, const SurfaceSet& set, double rho_c, bool per_node,
                   const std::string& who);

  /// Number of ERP components c_k (the rank of G kept).
  int components() const { return static_cast<int>(W_.rows()); }
  /// Number of elastic ERP components e_k (the rank of G_e kept).
  int elastic_components() const { return static_cast<int>(We_.rows()); }
  int values() const { return 5 + components() + elastic_components() + (per_node_ ? nodes() : 0); }
  int nodes() const { return static_cast<int>(B_.rows()); }
  double rho_c() const { return rho_c_; }
  double total_area() const { return area_; }

  /// out: vn_mean [m/s], vn_rms [m/s], erp [W], erp_elastic [W], erp_rigid [W],
  /// c_0 .. c_{K'-1} [W^0.5], e_0 .. e_{K_e'-1} [W^0.5], then (per_node) v_n of
  /// each node [m/s], from the LOF state and the body's modal velocities. No
  /// allocation.
  void evaluate(const LofState& lof, const double* qdot, double* out) const;

 private:
  double rho_c_ = 0.0, area_ = 0.0;
  bool per_node_ = false;
  Mat W_;                    ///< K' x K: rows sqrt(rho c lambda_k) e_k^T
  Mat We_;                   ///< K_e' x K: rows sqrt(rho c mu_k) f_k^T (the elastic part)
  Mat Wr_;                   ///< K_r' x K: the same for the rigid part
  std::vector<char> rigid_;  ///< K: 1 where u's entry is a rigid-body velocity
  Vec a_;                    ///< K: sum_i A_i b_i / sum A_i (the mean normal velocity is a . u)
  Mat B_;                    ///< nodes x K, per_node only
  mutable Vec u_, c_, ce_, cr_;
};

}  // namespace evas
