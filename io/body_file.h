// Modal-body files (HDF5): the hand-over from an FE program (or `evas body`)
// to a simulation. Layout in docs/body-format.md:
//   attributes  format = "evas-modal-body", version = 1, name, length_unit = "m",
//               mass_unit = "kg"
//   /nodes/ids (N, int64), /nodes/coordinates (N x 3, m)
//   /mass/lumped (N, kg)  or  /mass/consistent/{indptr, indices, values} (CSR, N x N)
//   /modes/eigenvalues (n, rad^2/s^2), /modes/shapes (3N x n, row 3i+a),
//   /modes/damping (n, 1/s), /modes/kind (n, 0 rigid / 1 elastic)
//   /sets/<name> (int64 node ids)
#pragma once

#include <string>

#include "solver/modal_body.h"

namespace evas {

inline constexpr const char* kBodyFormat = "evas-modal-body";
inline constexpr int kBodyFormatVersion = 1;

/// Writes `body` to `path` (overwriting). Throws InputError naming the file
/// when the body is inconsistent or the file cannot be written.
void write_body_file(const std::string& path, const ModalBody& body);

/// Reads and validates a modal-body file. Throws InputError naming the file and
/// the dataset or attribute that is missing or malformed.
ModalBody read_body_file(const std::string& path);

}  // namespace evas
