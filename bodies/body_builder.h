// Modal-body builder: from sparse stiffness and mass plus node coordinates to a
// ModalBody with an explicit mass-orthonormal rigid basis (formulation.md s. 2).
//
// Lowest modes of the shifted pencil M x = nu (K + s M) x (lambda = 1/nu - s),
// well posed also when the consistent mass is only semi-definite (coarse C10
// meshes), by dense Eigen (small models) or Spectra with a sparse Cholesky of
// K + s M (large); the six eigenvectors with the largest rigid-body content are
// replaced by rigid_basis(), the elastic modes are re-orthogonalised against it
// and each other in the mass inner product, then truncated by count and/or
// frequency cut-off.
#pragma once

#include "bodies/truss.h"
#include "model/modal_body.h"

namespace evas {

struct BuildOptions {
  int num_elastic = 0;         ///< keep at most this many elastic modes (0 = no count limit)
  double max_frequency = 0.0;  ///< keep elastic modes below this [Hz] (0 = no cut-off)
  bool keep_rigid = true;      ///< include the 6 rigid modes first
  double damping_ratio = 0.0;  ///< modal damping ratio for elastic modes
  std::string solver =
      "auto";  ///< "dense", "spectra" or "auto" (Spectra from 600 DOF when truncated)
};

ModalBody build_modal_body(const std::string& name, const FeModel& fe, const BuildOptions& opt);

/// A body from the FE model's nodes, mass and sets plus mass-orthonormal elastic
/// shapes (3N x m, free of rigid motion) and their eigenvalues: the explicit rigid
/// basis first when opt.keep_rigid, modal damping 2 zeta omega from
/// opt.damping_ratio, validated. Used by the builder and by importers of modes.
ModalBody assemble_modal_body(const std::string& name, const FeModel& fe, const Mat& elastic,
                              const Vec& eigenvalues, const BuildOptions& opt);

}  // namespace evas
