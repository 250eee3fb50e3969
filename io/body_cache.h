// Modal-body files read once per process. A study or sweep parses its scene
// many times (a probe per grid point, one parse per run); the body files are
// the same each time, and reading them (and the modal-contract check) is most
// of a parse. read_body_file_cached returns the body read earlier when the
// file's path, size and modification time are unchanged, else reads it again.
#pragma once

#include <string>

#include "model/modal_body.h"

namespace evas {

/// read_body_file(path), from the cache when the file has not changed.
ModalBody read_body_file_cached(const std::string& path);

}  // namespace evas
