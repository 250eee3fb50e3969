// Modal-body files (HDF5): the hand-over from an FE program (or `evas body`)
// to a simulation. Layout in docs/body-format.md:
//   attributes  format = "evas-modal-body", version = 2 (1 is read too), name,
//               length_unit = "m", mass_unit = "kg"; v2: reduced (0/1), full_num_nodes
//   /nodes/ids (N, int64), /nodes/coordinates (N x 3, m)
//   /mass/lumped (N, kg)  or  /mass/consistent/{indptr, indices, values} (CSR, N x N)
//               (absent in a reduced body)
//   /modes/eigenvalues (n, rad^2/s^2), /modes/shapes (3N x n, row 3i+a),
//   /modes/damping (n, 1/s), /modes/kind (n, 0 rigid / 1 elastic)
//   /sets/<name> (int64 node ids)
//   v2, optional (required in a reduced body), of the full body:
//   /invariants/S (3 x n), /invariants/p (3 x 3 x n), /invariants/M (3 x 3 x n x n)
//   /mass_properties/{mass (1), centre_of_mass (3), inertia (3 x 3),
//                     principal_moments (3), principal_axes (3 x 3, columns)}
#pragma once

#include <string>

#include "model/modal_body.h"

namespace evas {

inline constexpr const char* kBodyFormat = "evas-modal-body";
inline constexpr int kBodyFormatVersion = 2;  ///< written; versions 1 and 2 are read

/// Writes `body` to `path` (overwriting). Throws InputError naming the file
/// when the body is inconsistent or the file cannot be written.
void write_body_file(const std::string& path, const ModalBody& body);

/// Reads and validates a modal-body file (version 1 or 2); sets body.source to
/// `path`. Throws InputError naming the file and the dataset or attribute that
/// is missing or malformed. Before a dataset is read its declared shape is
/// checked against a limit (2^31 - 1 values) and against the bytes the file
/// stores for it (a truncated or forged file is refused, never allocated);
/// both a lumped and a consistent mass, and repeated ids in a node set, are
/// refused. The modal contract (orthonormal modes, rigid modes rigid, ...) is
/// checked separately: solver/modal_contract.h (scenes and `evas info` apply it).
ModalBody read_body_file(const std::string& path);

}  // namespace evas
