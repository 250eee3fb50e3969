// Modal-body files read once per process. A study or sweep parses its scene
// many times (a probe per grid point, one parse per run); the body files are
// the same each time, and reading them, checking the modal contract,
// truncating the modes and fitting the set markers is most of a parse.
//
// read_body_file_cached returns the body read earlier when the file's path,
// size, inode and modification time are unchanged, else reads it again.
// derived_body_cached keeps the body a scene makes of such a file (checked,
// truncated, damped) as one shared, immutable object per recipe, so that a
// parse copies nothing; set_marker_cached fits a set marker on such a body
// once, and surface_radiation_cached forms a surface output's ERP matrix on it
// once. Everything here is process-local and thread-safe.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/marker.h"
#include "model/modal_body.h"
#include "model/surface.h"

namespace evas {

/// read_body_file(path), from the cache when the file has not changed (a file
/// is kept from its second read on: the first is usually its only one).
ModalBody read_body_file_cached(const std::string& path);

/// derive(read_body_file_cached(path)), made once per file state and `recipe`
/// (the text of everything derive depends on besides the file) and shared.
/// What derive throws is thrown, and nothing is kept.
std::shared_ptr<const ModalBody> derived_body_cached(
    const std::string& path, const std::string& recipe,
    const std::function<ModalBody(ModalBody)>& derive);

/// make_set_marker(name, body, *data, ...), the fit made once per body, node
/// list, weights and centre when `data` is a body of derived_body_cached
/// (other bodies are fitted each time).
Marker set_marker_cached(const std::string& name, int body,
                         const std::shared_ptr<const ModalBody>& data,
                         const std::vector<long>& node_ids, const std::vector<double>& weights,
                         const Vec3* centre);

/// SurfaceRadiation(*data, set, rho_c, per_node, who), formed once per body,
/// set (by its content), rho_c and per_node when `data` is a body of
/// derived_body_cached (other bodies are formed each time), and copied out.
SurfaceRadiation surface_radiation_cached(const std::shared_ptr<const ModalBody>& data,
                                          const SurfaceSet& set, double rho_c, bool per_node,
                                          const std::string& who);

}  // namespace evas
