// Scene files (YAML): bodies, markers, elements, integrator, time span,
// outputs and operating point (the load; the speed is the crank LOF's) of one
// simulation. The format is described in docs/user-guide.md
// ("Scene files"). Every error is an InputError of the form
//     <file>:<line>: <item>: <what is wrong>
// and every unknown key is an error. Element parameters are read through the
// element registry (elements/registry.h), never hard-coded here.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.h"
#include "model/model.h"

namespace evas {

/// One `output.channels` entry, resolved against the model.
struct ChannelRequest {
  enum class Kind { Marker, Element, Modal, Torsion, Surface };
  /// What a marker request gives (bits): position, velocity, acceleration,
  /// angular velocity, angular acceleration.
  enum Quantity : unsigned {
    kPosition = 1,
    kVelocity = 2,
    kAcceleration = 4,
    kAngularVelocity = 8,
    kAngularAcceleration = 16
  };
  Kind kind = Kind::Marker;
  std::string name;                             ///< marker, element or body name
  int index = -1;                               ///< into Model::markers(), elements() or bodies()
  int line = 0;                                 ///< line in the scene file (1-based)
  unsigned quantities = kPosition | kVelocity;  ///< marker requests
  bool local = false;  ///< marker requests: components in the marker's own axes
  /// Torsion requests ({torsion: [A, B], name: N, axis: [x, y, z]}): `index` is
  /// marker A, `index2` marker B (both on one body), `name` the channels'
  /// prefix; `axis` the twist axis in the body's axes (zero: its LOF's spin axis).
  int index2 = -1;
  Vec3 axis = Vec3::Zero();
  /// Surface requests ({surface: SET, body: B, name: N, ...}, docs/theory.md
  /// section 8.3): `index` is body B, `set` its node set, `surface` the set's
  /// areas and normals (the body file's, or given in the scene), `rho_c` the
  /// characteristic impedance of the fluid [kg/(m^2 s)], `per_node` adds the
  /// normal velocity of every node.
  std::string set;
  std::shared_ptr<const SurfaceSet> surface;
  double rho_c = 413.0;
  bool per_node = false;
};

struct OutputSpec {
  std::string grid = "time";  ///< "time" or "crank-angle"
  double step = 1e-4;         ///< [s] for the time grid, [deg] for crank-angle
  std::string crank_body;     ///< crank-angle: body whose spin LOF gives the angle
  double start = 0.0;         ///< first output time [s] or crank angle [deg]
  bool start_given = false;   ///< false: start at t_start (or its crank angle)
  std::vector<ChannelRequest> channels;
};

struct Scene {
  std::string name;
  std::string text;  ///< the scene file as read
  std::string path;
  std::unique_ptr<Model> model;
  IntegratorSettings integrator;
  double t_start = 0.0, t_end = 0.0;
  OutputSpec output;
  /// Plausibility warnings (elements/plausibility.h), in file order, each
  /// naming the file, line and item: values that are likely unit slips.
  std::vector<std::string> warnings;
};

/// Reads a scene file; body files are resolved relative to its directory.
/// The text of a scene file, checked first to be a regular file of at most
/// 16 MiB (a device or pipe never ends). Throws InputError naming the file.
std::string read_scene_text(const std::string& path);
Scene read_scene(const std::string& path);
/// Parses scene text as if read from `path` (for tests; `path` names the file
/// in messages and anchors relative body-file paths).
Scene parse_scene(const std::string& text, const std::string& path);

}  // namespace evas
