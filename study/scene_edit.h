// Scene overrides of a study (`--param ITEM.KEY=VALUE`): a scene parameter is
// changed in the YAML text before the scene is parsed, so every check of the
// scene reader applies to the changed value too.
//
//   ITEM  a glob ('*', '?') over the `name` of the scene's bodies, markers and
//         elements (every match is changed), or a top-level mapping such as
//         `time`, `integrator`, `output`, `operating_point` (created when
//         the scene has none: `operating_point.load=0.5` on any scene);
//   KEY   the key in that item; dots go deeper (`shaft.lof.speed`);
//   VALUE a YAML value: a scalar (`3e-5`, `quadrature`) or a flow list (`[1e6, 1e6, 1e6]`).
//
// The edited document is re-emitted as YAML and parsed with
// parse_scene(text, original path), so relative body paths still resolve.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/scene.h"

namespace evas::study {

/// Applies "ITEM.KEY=VALUE" assignments to scene text. `option` names the
/// option in messages. Throws InputError naming the assignment (unknown item,
/// malformed text). Without assignments the text is returned unchanged.
std::string edit_scene_text(const std::string& text, const std::vector<std::string>& params,
                            const std::string& option = "--param");

/// A scene file with overrides, kept as text so every run parses its own model.
struct SceneSource {
  std::string path;     ///< the scene file (anchors relative body paths)
  std::string text;     ///< the edited text
  bool edited = false;  ///< text was re-emitted (line numbers differ from the file's)

  /// parse_scene(text, path); errors in an edited scene say so.
  Scene parse() const;
};

/// Reads `path` and applies `params`, then `time.end = t_end` when given.
SceneSource load_scene_source(const std::string& path, const std::vector<std::string>& params,
                              std::optional<double> t_end = std::nullopt);

/// The same source with more assignments applied.
SceneSource edited(const SceneSource& src, const std::vector<std::string>& params,
                   const std::string& option);

}  // namespace evas::study
