// The modal contract of a body (docs/body-format.md): what the equations of
// motion assume of the modes, checked with a measured value each.
//
//   mode count             at least one mode
//   finite values          no NaN/Inf in coordinates, mass, modes, eigenvalues, damping
//   non-zero shapes        no mode whose shape is zero everywhere
//   elastic eigenvalues    every elastic mode has lambda > 0
//   rigid eigenvalues      every rigid mode has |lambda| <= tol * max |lambda| (round-off)
//   mass normalisation     max_k |(Phi^T M Phi)_kk - 1| <= tol
//   mass orthogonality     max_{j != k} |(Phi^T M Phi)_jk| <= tol
//   invariant symmetry     max |M_ab - M_ba^T| <= tol (a symmetric mass matrix)
//   rigid modes rigid      every rigid mode is a rigid-body motion:
//                          1 - |R^T M phi|^2 / phi^T M phi <= tol
//   elastic free of rigid  with rigid modes present, max |R^T M phi| <= tol over the
//                          elastic modes (R: the mass-orthonormal rigid basis)
//   stored vs nodes        stored invariants / mass properties of a full body agree
//                          with those recomputed from its nodes (relative, <= tol)
//
// Phi^T M Phi and R^T M Phi come from the nodes and the mass matrix of a full
// body, and from the stored invariants and mass properties of the full body in
// a reduced one (which has no mass matrix): the checks that need the full mass
// matrix itself (stored vs nodes) are skipped there, with the reason.
#pragma once

#include <string>
#include <vector>

#include "model/modal_body.h"

namespace evas {

/// Default tolerance of the relative checks (orthonormality, round-off of rigid
/// eigenvalues, stored data).
inline constexpr double kModalCheckTolerance = 1e-6;

struct ModalCheck {
  enum class Status { Pass, Fail, Skipped };
  std::string name;             ///< e.g. "mass normalisation"
  std::string measure;          ///< what `value` is, e.g. "max |diag(Phi^T M Phi) - 1|"
  double value = 0.0;           ///< measured (0 when skipped)
  std::string relation = "<=";  ///< the check passes when `value relation limit`
  double limit = 0.0;
  Status status = Status::Pass;
  std::string detail;     ///< where it fails, why it is skipped, or where the data came from
  bool relative = false;  ///< a relative check whose limit follows the tolerance
};

struct ModalContract {
  double tolerance = kModalCheckTolerance;
  std::vector<ModalCheck> checks;
  bool ok() const;
  /// First failed check, or nullptr.
  const ModalCheck* first_failure() const;
};

/// Runs every check on a body that passed ModalBody::validate() (sizes
/// consistent). Never throws for a bad body: failures are reported.
ModalContract check_modal_contract(const ModalBody& body, double tolerance = kModalCheckTolerance);

/// One line: "modal check 'NAME' failed: MEASURE = VALUE, must be <= LIMIT (DETAIL)".
std::string describe_failure(const ModalCheck& c);

/// Throws InputError "<file or body>: modal check '...' failed: ..." at the
/// first failed check.
void require_modal_contract(const ModalBody& body, double tolerance = kModalCheckTolerance);

}  // namespace evas
