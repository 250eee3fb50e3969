#include "io/scene.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "bodies/body_builder.h"
#include "bodies/cylinder_fit.h"
#include "bodies/modal_contract.h"
#include "bodies/truss.h"
#include "elements/registry.h"
#include "integrators/settings.h"
#include "io/body_file.h"
#include "io/outputs.h"
#include "solver/system.h"

namespace evas {

namespace {

using Node = YAML::Node;

// Limits checked before allocating or iterating: a scene file larger than
// this is refused before yaml-cpp parses it; lists longer than these are
// refused before they are walked.
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;  // 16 MiB
constexpr std::size_t kMaxSceneItems = 100000;        // bodies, markers, elements, channels
constexpr std::size_t kMaxListEntries = 1000000;      // numbers: node ids, weights, tables

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string number_text(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

// Reads one scene document. Every check names the file, the line and the item.
class SceneReader {
 public:
  SceneReader(std::string file, std::filesystem::path dir)
      : file_(std::move(file)), dir_(std::move(dir)) {}

  Scene read(const Node& root);

 private:
  // --- errors ---------------------------------------------------------------
  [[noreturn]] void fail(const Node& at, const std::string& item, const std::string& what) const {
    const int line = at.Mark().line >= 0 ? at.Mark().line + 1 : 0;
    throw InputError(file_ + ":" + std::to_string(line) + ": " + item + ": " + what);
  }
  // Re-raises an error from a library call, dropping a repeated item prefix.
  [[noreturn]] void rethrow(const Node& at, const std::string& item, const InputError& e) const {
    std::string msg = e.what();
    for (const std::string& prefix : {item + ": ", "marker '" + name_of(item) + "': "})
      if (msg.rfind(prefix, 0) == 0) msg = msg.substr(prefix.size());
    fail(at, item, msg);
  }
  static std::string name_of(const std::string& item) {
    const auto a = item.find('\''), b = item.rfind('\'');
    return a != std::string::npos && b > a ? item.substr(a + 1, b - a - 1) : item;
  }

  // --- structure ------------------------------------------------------------
  void expect_map(const Node& n, const std::string& item) const {
    if (!n.IsMap()) fail(n, item, "must be a mapping of keys to values");
  }
  void check_keys(const Node& map, const std::string& item,
                  const std::vector<std::string>& known) const {
    expect_map(map, item);
    std::set<std::string> seen;
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string key = it->first.as<std::string>();
      if (std::find(known.begin(), known.end(), key) == known.end())
        fail(it->first, item, "unknown key '" + key + "' (known: " + join(known) + ")");
      if (!seen.insert(key).second) fail(it->first, item, "key '" + key + "' is given twice");
    }
  }
  Node require(const Node& map, const std::string& key, const std::string& item) const {
    const Node v = map[key];
    if (!v) fail(map, item, "missing key '" + key + "'");
    return v;
  }

  // --- values ---------------------------------------------------------------
  double number(const Node& v, const std::string& item, const std::string& key) const {
    double x = 0.0;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, x))
      fail(v, item, "'" + key + "' must be a number" + got(v));
    if (!std::isfinite(x)) fail(v, item, "'" + key + "' must be finite");
    return x;
  }
  double number_in(const Node& v, const std::string& item, const std::string& key, double lo,
                   double hi, bool open_lo = false) const {
    const double x = number(v, item, key);
    if (x < lo || x > hi || (open_lo && x == lo)) {
      std::string range = open_lo ? "> " + number_text(lo) : ">= " + number_text(lo);
      if (hi < 1e300) range += " and <= " + number_text(hi);
      fail(v, item, "'" + key + "' = " + number_text(x) + " must be " + range);
    }
    return x;
  }
  long integer(const Node& v, const std::string& item, const std::string& key, long lo,
               long hi = LONG_MAX) const {
    long x = 0;
    if (!v.IsScalar() || !YAML::convert<long>::decode(v, x))
      fail(v, item, "'" + key + "' must be an integer" + got(v));
    if (x < lo)
      fail(v, item, "'" + key + "' = " + std::to_string(x) + " must be >= " + std::to_string(lo));
    if (x > hi)
      fail(v, item,
           "'" + key + "' = " + std::to_string(x) + " is more than the limit of " +
               std::to_string(hi));
    return x;
  }
  // A list longer than `limit` is refused before it is walked.
  void check_size(const Node& v, const std::string& item, const std::string& key,
                  std::size_t limit = kMaxListEntries) const {
    if (v.IsSequence() && v.size() > limit)
      fail(v, item,
           "'" + key + "' has " + std::to_string(v.size()) + " entries, more than the limit of " +
               std::to_string(limit));
  }
  bool boolean(const Node& v, const std::string& item, const std::string& key) const {
    bool x = false;
    if (!v.IsScalar() || !YAML::convert<bool>::decode(v, x))
      fail(v, item, "'" + key + "' must be true or false" + got(v));
    return x;
  }
  std::string text(const Node& v, const std::string& item, const std::string& key) const {
    if (!v.IsScalar() || v.Scalar().empty()) fail(v, item, "'" + key + "' must be a name or word");
    return v.Scalar();
  }
  std::string choice(const Node& v, const std::string& item, const std::string& key,
                     const std::vector<std::string>& choices) const {
    const std::string s = text(v, item, key);
    if (std::find(choices.begin(), choices.end(), s) == choices.end())
      fail(v, item, "'" + key + "' is '" + s + "', expected one of: " + join(choices));
    return s;
  }
  std::vector<double> numbers(const Node& v, const std::string& item,
                              const std::string& key) const {
    if (!v.IsSequence()) fail(v, item, "'" + key + "' must be a list of numbers" + got(v));
    check_size(v, item, key);
    std::vector<double> out;
    for (const Node& x : v) out.push_back(number(x, item, key));
    return out;
  }
  std::vector<double> numbers(const Node& v, const std::string& item, const std::string& key,
                              std::size_t size) const {
    if (!v.IsSequence())
      fail(v, item,
           "'" + key + "' must be a list of " + std::to_string(size) + " numbers" + got(v));
    if (v.size() != size)
      fail(v, item,
           "'" + key + "' must have " + std::to_string(size) + " values, got " +
               std::to_string(v.size()));
    return numbers(v, item, key);
  }
  Vec3 vec3(const Node& v, const std::string& item, const std::string& key) const {
    const auto x = numbers(v, item, key, 3);
    return Vec3(x[0], x[1], x[2]);
  }
  Vec3 vec3_or(const Node& map, const std::string& key, const std::string& item,
               const Vec3& def) const {
    const Node v = map[key];
    return v ? vec3(v, item, key) : def;
  }
  /// A set marker's `centre`: three numbers, or `fit` for the centre of the
  /// least-squares cylinder through the set's nodes (solver/cylinder_fit.h).
  Vec3 marker_centre(const Node& v, const std::string& item, const ModalBody& body,
                     const std::vector<long>& ids) const {
    if (!v.IsScalar()) return vec3(v, item, "centre");
    if (v.Scalar() != "fit")
      fail(v, item, "'centre' must be a list of 3 numbers or 'fit'" + got(v));
    std::vector<Vec3> pts;
    for (long id : ids) pts.push_back(body.s.row(body.node_index(id)).transpose());
    try {
      return fit_cylinder(pts).centre;
    } catch (const InputError& e) {
      fail(v, item, std::string("centre: fit: ") + e.what());
    }
  }
  static std::string got(const Node& v) {
    if (v.IsScalar()) return ", got '" + v.Scalar() + "'";
    if (v.IsSequence()) return ", got a list";
    if (v.IsMap()) return ", got a mapping";
    if (v.IsNull()) return ", got nothing";
    return "";
  }

  // --- sections -------------------------------------------------------------
  void read_body(const Node& b, std::size_t i, Model& model);
  std::shared_ptr<ModalBody> generate_body(const Node& g, const Node& modes,
                                           const std::string& name, const std::string& item,
                                           double zeta, bool has_zeta);
  ModalBody truncate(ModalBody body, const Node& modes, const std::string& item) const;
  Lof read_lof(const Node& l, const std::string& item) const;
  void read_marker(const Node& m, std::size_t i, Model& model);
  void read_element(const Node& e, std::size_t i, Model& model);
  void read_joint(const Node& e, std::size_t i, Model& model);
  IntegratorSettings read_integrator(const Node& n) const;
  OutputSpec read_output(const Node& n, const Model& model, double t_start, double t_end) const;

  std::string file_;
  std::filesystem::path dir_;
};

Scene SceneReader::read(const Node& root) {
  Scene scene;
  const std::string item = "scene";
  if (!root.IsMap()) {
    if (!root.IsDefined() || root.IsNull())
      throw InputError(file_ + ":1: scene: the file is empty");
    fail(root, item, "must be a mapping with keys name, bodies, markers, elements, ...");
  }
  check_keys(root, item,
             {"name", "description", "gravity", "bodies", "markers", "elements", "joints",
              "integrator", "time", "output"});
  scene.name = root["name"] ? text(root["name"], item, "name")
                            : std::filesystem::path(file_).stem().string();
  scene.model = std::make_unique<Model>();
  Model& model = *scene.model;
  if (root["description"]) text(root["description"], item, "description");
  model.gravity = vec3_or(root, "gravity", item, Vec3::Zero());

  const Node bodies = require(root, "bodies", item);
  if (!bodies.IsSequence() || bodies.size() == 0)
    fail(bodies, "bodies", "must be a list of at least one body");
  check_size(bodies, "scene", "bodies", kMaxSceneItems);
  for (std::size_t i = 0; i < bodies.size(); ++i) read_body(bodies[i], i, model);

  if (const Node markers = root["markers"]) {
    if (!markers.IsSequence()) fail(markers, "markers", "must be a list of markers");
    check_size(markers, "scene", "markers", kMaxSceneItems);
    for (std::size_t i = 0; i < markers.size(); ++i) read_marker(markers[i], i, model);
  }
  if (const Node elements = root["elements"]) {
    if (!elements.IsSequence()) fail(elements, "elements", "must be a list of elements");
    check_size(elements, "scene", "elements", kMaxSceneItems);
    for (std::size_t i = 0; i < elements.size(); ++i) read_element(elements[i], i, model);
  }
  if (const Node joints = root["joints"]) {
    if (!joints.IsSequence()) fail(joints, "joints", "must be a list of joints");
    check_size(joints, "scene", "joints", kMaxSceneItems);
    for (std::size_t i = 0; i < joints.size(); ++i) read_joint(joints[i], i, model);
    // what needs the frames and all joints together (geometry, dependence)
    try {
      const System check(model);
    } catch (const InputError& err) {
      fail(joints, "joints", err.what());
    }
  }
  if (const Node integ = root["integrator"]) scene.integrator = read_integrator(integ);

  const Node time = require(root, "time", item);
  check_keys(time, "time", {"start", "end"});
  scene.t_start = time["start"] ? number(time["start"], "time", "start") : 0.0;
  const Node end = require(time, "end", "time");
  scene.t_end = number(end, "time", "end");
  if (!(scene.t_end > scene.t_start))
    fail(end, "time",
         "'end' = " + number_text(scene.t_end) + " must be > start (" + number_text(scene.t_start) +
             ")");

  if (const Node out = root["output"]) {
    scene.output = read_output(out, model, scene.t_start, scene.t_end);
  } else {
    scene.output.step = (scene.t_end - scene.t_start) / 1000.0;
    scene.output.start = scene.t_start;
  }
  return scene;
}

void SceneReader::read_body(const Node& b, std::size_t i, Model& model) {
  std::string item = "bodies[" + std::to_string(i) + "]";
  expect_map(b, item);
  const std::string name = text(require(b, "name", item), item, "name");
  item += " '" + name + "'";
  check_keys(
      b, item,
      {"name", "file", "generate", "modes", "damping_ratio", "lof", "initial", "check_tolerance"});
  for (const auto& other : model.bodies())
    if (other.name == name) fail(b["name"], item, "a body with this name is already defined");

  const Node file = b["file"], gen = b["generate"], modes = b["modes"];
  if (bool(file) == bool(gen)) fail(b, item, "give exactly one of 'file' and 'generate'");
  const Node zeta_node = b["damping_ratio"];
  const double zeta = zeta_node ? number_in(zeta_node, item, "damping_ratio", 0.0, 10.0) : 0.0;
  if (modes) check_keys(modes, item + " modes", {"rigid", "elastic", "max_frequency"});

  std::shared_ptr<ModalBody> data;
  const Node tol_node = b["check_tolerance"];
  if (tol_node && gen)
    fail(tol_node, item, "'check_tolerance' applies to body files ('file') only");
  const double tolerance = tol_node ? number_in(tol_node, item, "check_tolerance", 0.0, 1.0, true)
                                    : kModalCheckTolerance;
  if (gen) {
    data = generate_body(gen, modes, name, item, zeta, bool(zeta_node));
  } else {
    const std::string rel = text(file, item, "file");
    std::filesystem::path p(rel);
    if (p.is_relative()) p = dir_ / p;
    ModalBody body;
    try {
      body = read_body_file(p.string());
    } catch (const InputError& e) {
      fail(file, item, e.what());
    }
    // The modal contract (orthonormal modes, rigid modes rigid, ...) of the
    // file as written, before any truncation.
    const ModalContract contract = check_modal_contract(body, tolerance);
    if (const ModalCheck* f = contract.first_failure())
      fail(file, item,
           body.source + ": " + describe_failure(*f) +
               (f->relative ? "; 'check_tolerance' (default " + number_text(kModalCheckTolerance) +
                                  ") relaxes the relative checks"
                            : std::string()));
    body.name = name;
    body = truncate(std::move(body), modes, item);
    if (zeta_node)
      for (int k = 0; k < body.num_modes(); ++k)
        body.damping[k] = body.kinds[k] == ModeKind::Elastic
                              ? 2.0 * zeta * std::sqrt(std::max(0.0, body.eigenvalues[k]))
                              : 0.0;
    data = std::make_shared<ModalBody>(std::move(body));
  }
  if (data->num_modes() == 0) fail(modes ? modes : b, item, "no modes left after truncation");

  const Node lof_node = b["lof"];
  const Lof lof =
      lof_node ? read_lof(lof_node, item + " lof") : Lof::fixed(Vec3::Zero(), Mat3::Identity());
  int index = -1;
  try {
    index = model.add_body(name, data, lof);
  } catch (const InputError& e) {
    rethrow(b, item, e);
  }
  if (const Node init = b["initial"]) {
    const std::string it = item + " initial";
    check_keys(init, it, {"q", "v"});
    Body& body = model.bodies()[index];
    const std::size_t n = static_cast<std::size_t>(body.n());
    if (init["q"]) {
      const auto q = numbers(init["q"], it, "q", n);
      body.q0 = Eigen::Map<const Vec>(q.data(), body.n());
    }
    if (init["v"]) {
      const auto v = numbers(init["v"], it, "v", n);
      body.v0 = Eigen::Map<const Vec>(v.data(), body.n());
    }
  }
}

std::shared_ptr<ModalBody> SceneReader::generate_body(const Node& g, const Node& modes,
                                                      const std::string& name,
                                                      const std::string& item, double zeta,
                                                      bool has_zeta) {
  const std::string it = item + " generate";
  check_keys(g, it, {"type", "segments", "length", "width", "youngs", "area", "density", "origin"});
  choice(require(g, "type", it), it, "type", {"truss-beam"});
  TrussBeamSpec spec;
  const double inf = 1e300;
  if (g["segments"])
    spec.segments = static_cast<int>(integer(g["segments"], it, "segments", 1, kMaxTrussSegments));
  if (g["length"]) spec.length = number_in(g["length"], it, "length", 0.0, inf, true);
  if (g["width"]) spec.width = number_in(g["width"], it, "width", 0.0, inf, true);
  if (g["youngs"]) spec.youngs = number_in(g["youngs"], it, "youngs", 0.0, inf, true);
  if (g["area"]) spec.area = number_in(g["area"], it, "area", 0.0, inf, true);
  if (g["density"]) spec.density = number_in(g["density"], it, "density", 0.0, inf, true);
  spec.origin = vec3_or(g, "origin", it, Vec3::Zero());

  BuildOptions opt;
  opt.damping_ratio = has_zeta ? zeta : 0.0;
  bool rigid_only = false;
  const long nodes = 4L * (spec.segments + 1), dof = 3 * nodes;
  const std::string mi = item + " modes";
  if (modes) {
    if (modes["rigid"]) opt.keep_rigid = boolean(modes["rigid"], mi, "rigid");
    if (const Node el = modes["elastic"]) {
      const long k = integer(el, mi, "elastic", 0);
      if (k > dof - 6)
        fail(el, mi,
             "'elastic' = " + std::to_string(k) + ", but the generated truss has only " +
                 std::to_string(dof - 6) + " elastic modes (" + std::to_string(nodes) +
                 " nodes, 3 x " + std::to_string(nodes) + " - 6)");
      if (k > kMaxGeneratedModes)
        fail(el, mi,
             "'elastic' = " + std::to_string(k) + " is more than the limit of " +
                 std::to_string(kMaxGeneratedModes) + " modes of a generated body");
      opt.num_elastic = static_cast<int>(k);
      rigid_only = k == 0;
      if (rigid_only) opt.num_elastic = 1;  // only the rigid basis is kept: no full solve
    }
    if (modes["max_frequency"])
      opt.max_frequency = number_in(modes["max_frequency"], mi, "max_frequency", 0.0, inf, true);
  }
  if (opt.num_elastic == 0 && dof > kMaxDenseDof)
    fail(modes && modes["max_frequency"] ? modes["max_frequency"] : g, modes ? mi : it,
         "the generated truss has " + std::to_string(dof) + " DOF (" +
             std::to_string(spec.segments) +
             " segments); without an 'elastic' count every mode below the cut-off may be "
             "needed, which takes the dense eigen-solver, limited to " +
             std::to_string(kMaxDenseDof) + " DOF: give 'modes: {elastic: K}'");
  ModalBody body;
  try {
    body = build_modal_body(name, make_truss_beam(spec), opt);
  } catch (const InputError& e) {
    rethrow(g, it, e);
  }
  if (rigid_only) {
    std::vector<int> keep;
    for (int k = 0; k < body.num_modes(); ++k)
      if (body.kinds[k] == ModeKind::Rigid) keep.push_back(k);
    body = body.select_modes(keep);
  }
  return std::make_shared<ModalBody>(std::move(body));
}

ModalBody SceneReader::truncate(ModalBody body, const Node& modes, const std::string& item) const {
  if (!modes) return body;
  const std::string mi = item + " modes";
  const bool rigid = modes["rigid"] ? boolean(modes["rigid"], mi, "rigid") : true;
  const long elastic = modes["elastic"] ? integer(modes["elastic"], mi, "elastic", 0) : -1;
  const double fmax = modes["max_frequency"]
                          ? number_in(modes["max_frequency"], mi, "max_frequency", 0.0, 1e300, true)
                          : 0.0;
  std::vector<int> rigid_modes, elastic_modes;
  for (int k = 0; k < body.num_modes(); ++k) {
    if (body.kinds[k] == ModeKind::Rigid) {
      if (rigid) rigid_modes.push_back(k);
      continue;
    }
    const double f = std::sqrt(std::max(0.0, body.eigenvalues[k])) / (2.0 * M_PI);
    if (fmax > 0.0 && f > fmax) continue;
    elastic_modes.push_back(k);
  }
  std::stable_sort(elastic_modes.begin(), elastic_modes.end(),
                   [&](int a, int b) { return body.eigenvalues[a] < body.eigenvalues[b]; });
  if (elastic > static_cast<long>(elastic_modes.size()) && fmax == 0.0)
    fail(modes["elastic"], mi,
         "'elastic' = " + std::to_string(elastic) + ", but the body file has only " +
             std::to_string(elastic_modes.size()) + " elastic modes");
  if (elastic >= 0 && static_cast<long>(elastic_modes.size()) > elastic)
    elastic_modes.resize(static_cast<std::size_t>(elastic));
  std::vector<int> keep = rigid_modes;
  keep.insert(keep.end(), elastic_modes.begin(), elastic_modes.end());
  return body.select_modes(keep);
}

Lof SceneReader::read_lof(const Node& l, const std::string& item) const {
  expect_map(l, item);
  const std::string kind =
      choice(require(l, "kind", item), item, "kind", {"fixed", "spin", "tracking"});
  const Vec3 origin = vec3_or(l, "origin", item, Vec3::Zero());
  const Mat3 R = rotation_from_vector(vec3_or(l, "rotation", item, Vec3::Zero()));
  try {
    if (kind == "fixed") {
      check_keys(l, item, {"kind", "origin", "rotation", "velocity", "acceleration"});
      Lof lof = Lof::fixed(origin, R);
      lof.set_origin_motion(vec3_or(l, "velocity", item, Vec3::Zero()),
                            vec3_or(l, "acceleration", item, Vec3::Zero()));
      return lof;
    }
    if (kind == "spin") {
      check_keys(l, item,
                 {"kind", "axis", "origin", "rotation", "speed", "speed_profile", "angle",
                  "velocity", "acceleration"});
      const Node axis_node = require(l, "axis", item);
      const Vec3 axis = vec3(axis_node, item, "axis");
      if (!(axis.norm() > 0.0)) fail(axis_node, item, "'axis' must not be zero");
      const Node speed = l["speed"], profile = l["speed_profile"];
      if (bool(speed) == bool(profile))
        fail(l, item, "give exactly one of 'speed' and 'speed_profile'");
      std::vector<double> times, speeds;
      if (speed) {
        times = {0.0};
        speeds = {number(speed, item, "speed")};
      } else {
        if (!profile.IsSequence() || profile.size() == 0)
          fail(profile, item, "'speed_profile' must be a list of [time, speed] pairs");
        check_size(profile, item, "speed_profile");
        for (const Node& pair : profile) {
          const auto tw = numbers(pair, item, "speed_profile", 2);
          if (!times.empty() && !(tw[0] > times.back()))
            fail(pair, item, "'speed_profile' times must increase strictly");
          times.push_back(tw[0]);
          speeds.push_back(tw[1]);
        }
      }
      const double angle = l["angle"] ? number(l["angle"], item, "angle") : 0.0;
      Lof lof = Lof::spin(origin, R, axis, angle, times, speeds);
      lof.set_origin_motion(vec3_or(l, "velocity", item, Vec3::Zero()),
                            vec3_or(l, "acceleration", item, Vec3::Zero()));
      return lof;
    }
    check_keys(l, item, {"kind", "origin", "rotation", "interval", "velocity", "angular_velocity"});
    const double interval =
        number_in(require(l, "interval", item), item, "interval", 0.0, 1e300, true);
    return Lof::tracking(origin, R, vec3_or(l, "velocity", item, Vec3::Zero()),
                         vec3_or(l, "angular_velocity", item, Vec3::Zero()), interval);
  } catch (const InputError& e) {
    const std::string msg = e.what();
    if (msg.rfind(file_ + ":", 0) == 0) throw;
    fail(l, item, msg);
  }
}

void SceneReader::read_marker(const Node& m, std::size_t i, Model& model) {
  std::string item = "markers[" + std::to_string(i) + "]";
  expect_map(m, item);
  const std::string name = text(require(m, "name", item), item, "name");
  item = "marker '" + name + "'";
  for (const auto& other : model.markers())
    if (other.name == name) fail(m["name"], item, "a marker with this name is already defined");
  Marker marker;
  if (const Node g = m["ground"]) {
    check_keys(m, item, {"name", "ground", "rotation"});
    const Mat3 R = rotation_from_vector(vec3_or(m, "rotation", item, Vec3::Zero()));
    marker = make_ground_marker(name, vec3(g, item, "ground"), R);
  } else {
    check_keys(m, item, {"name", "body", "node", "set", "nodes", "weights", "centre", "rotation"});
    const Node body_node = require(m, "body", item);
    const std::string body_name = text(body_node, item, "body");
    int body = -1;
    std::vector<std::string> known;
    for (std::size_t k = 0; k < model.bodies().size(); ++k) {
      known.push_back(model.bodies()[k].name);
      if (model.bodies()[k].name == body_name) body = static_cast<int>(k);
    }
    if (body < 0)
      fail(body_node, item, "no body named '" + body_name + "' (known: " + join(known) + ")");
    const ModalBody& data = *model.bodies()[body].data;
    const Node node = m["node"], set = m["set"], nodes = m["nodes"];
    if (int(bool(node)) + int(bool(set)) + int(bool(nodes)) != 1)
      fail(m, item,
           "give exactly one of 'node', 'set' and 'nodes' (or 'ground' for a ground marker)");
    try {
      if (node) {
        if (m["weights"] || m["centre"])
          fail(m, item, "'weights' and 'centre' apply to 'set' or 'nodes' markers only");
        marker = make_node_marker(name, body, data, integer(node, item, "node", -(1L << 62)));
      } else {
        std::vector<long> ids;
        if (set) {
          const std::string set_name = text(set, item, "set");
          const auto it = data.node_sets.find(set_name);
          if (it == data.node_sets.end()) {
            std::vector<std::string> sets;
            for (const auto& s : data.node_sets) sets.push_back(s.first);
            fail(set, item,
                 "body '" + body_name + "' has no node set '" + set_name +
                     "' (known: " + join(sets) + ")");
          }
          ids = it->second;
        } else {
          if (!nodes.IsSequence()) fail(nodes, item, "'nodes' must be a list of node ids");
          check_size(nodes, item, "nodes");
          std::set<long> seen;
          for (const Node& x : nodes) {
            ids.push_back(integer(x, item, "nodes", -(1L << 62)));
            if (!seen.insert(ids.back()).second)
              fail(x, item,
                   "node id " + std::to_string(ids.back()) +
                       " is listed twice in 'nodes' (each node once; use 'weights' to weight "
                       "it)");
          }
        }
        std::vector<double> weights;
        if (m["weights"]) weights = numbers(m["weights"], item, "weights", ids.size());
        Vec3 centre;
        const bool has_centre = bool(m["centre"]);
        if (has_centre) centre = marker_centre(m["centre"], item, data, ids);
        marker = make_set_marker(name, body, data, ids, weights, has_centre ? &centre : nullptr);
      }
    } catch (const InputError& e) {
      const std::string msg = e.what();
      if (msg.rfind(file_ + ":", 0) == 0) throw;
      rethrow(node ? node : set ? set : nodes, item, e);
    }
    if (m["rotation"]) marker.R_LM = rotation_from_vector(vec3(m["rotation"], item, "rotation"));
  }
  try {
    model.add_marker(std::move(marker));
  } catch (const InputError& e) {
    rethrow(m, item, e);
  }
}

void SceneReader::read_element(const Node& e, std::size_t i, Model& model) {
  std::string item = "elements[" + std::to_string(i) + "]";
  expect_map(e, item);
  const std::string name = text(require(e, "name", item), item, "name");
  item = "element '" + name + "'";
  for (const auto& other : model.elements())
    if (other->name() == name)
      fail(e["name"], item, "an element with this name is already defined");
  const Node type_node = require(e, "type", item);
  const ElementType* type = nullptr;
  try {
    type = &element_type(text(type_node, item, "type"));
  } catch (const InputError& err) {
    const std::string msg = err.what();
    if (msg.rfind(file_ + ":", 0) == 0) throw;
    fail(type_node, item, msg);
  }
  std::vector<std::string> known = {"name", "type", "markers"};
  for (const auto& p : type->params) known.push_back(p.key);
  check_keys(e, item, known);

  const Node markers = require(e, "markers", item);
  if (!markers.IsSequence())
    fail(markers, item, "'markers' must be a list of marker names" + got(markers));
  check_size(markers, item, "markers", kMaxSceneItems);
  if (type->num_markers > 0 && static_cast<int>(markers.size()) != type->num_markers)
    fail(markers, item,
         "type '" + type->type + "' needs " + std::to_string(type->num_markers) + " markers, got " +
             std::to_string(markers.size()));
  if (type->num_markers <= 0 && markers.size() < 2)
    fail(markers, item,
         "type '" + type->type + "' needs two or more markers, got " +
             std::to_string(markers.size()));
  std::vector<int> idx;
  for (const Node& mk : markers) {
    const std::string mname = text(mk, item, "markers");
    int found = -1;
    std::vector<std::string> names;
    for (std::size_t k = 0; k < model.markers().size(); ++k) {
      names.push_back(model.markers()[k].name);
      if (model.markers()[k].name == mname) found = static_cast<int>(k);
    }
    if (found < 0) fail(mk, item, "no marker named '" + mname + "' (known: " + join(names) + ")");
    idx.push_back(found);
  }

  ParamValues values;
  for (const ParamSpec& spec : type->params) {
    const Node v = e[spec.key];
    if (!v) continue;
    const std::string where = file_ + ":" + std::to_string(v.Mark().line + 1) + ": " + item;
    const std::string head = "parameter '" + spec.key + "'";
    if (spec.kind == ParamSpec::Kind::Text) {
      if (!v.IsScalar()) fail(v, item, head + " must be text" + got(v));
      if (!spec.choices.empty() &&
          std::find(spec.choices.begin(), spec.choices.end(), v.Scalar()) == spec.choices.end())
        fail(v, item, head + " is '" + v.Scalar() + "', expected one of: " + join(spec.choices));
      std::string value = v.Scalar();
      if (spec.is_path && !value.empty() && std::filesystem::path(value).is_relative())
        value = (dir_ / value).string();  // paths are relative to the scene file
      values.texts[spec.key] = value;
      continue;
    }
    std::vector<double> x;
    auto push = [&](const Node& s) {
      double d = 0.0;
      if (!s.IsScalar() || !YAML::convert<double>::decode(s, d))
        fail(s, item, head + " must be numbers" + got(s));
      x.push_back(d);
    };
    if (v.IsScalar()) {
      push(v);
    } else if (v.IsSequence()) {
      check_size(v, item, spec.key);
      for (const Node& s : v) {
        check_size(s, item, spec.key);
        if (s.IsSequence() && spec.kind == ParamSpec::Kind::List) {
          for (const Node& ss : s) push(ss);  // tables: rows flattened
        } else {
          push(s);
        }
      }
    } else {
      fail(v, item,
           head + " must be " +
               (spec.kind == ParamSpec::Kind::Scalar ? "a number" : "a list of numbers") + got(v));
    }
    check_param(spec, x, where);
    values.numbers[spec.key] = x;
  }
  try {
    complete_params(*type, values, file_ + ":" + std::to_string(e.Mark().line + 1) + ": " + item);
    model.add_element(type->make(name, idx, values));
  } catch (const InputError& err) {
    const std::string msg = err.what();
    if (msg.rfind(file_ + ":", 0) == 0) throw;
    rethrow(e, item, err);
  }
}

void SceneReader::read_joint(const Node& e, std::size_t i, Model& model) {
  std::string item = "joints[" + std::to_string(i) + "]";
  expect_map(e, item);
  const std::string name = text(require(e, "name", item), item, "name");
  item = "joint '" + name + "'";
  check_keys(e, item, {"name", "type", "markers", "length"});
  Joint j;
  j.name = name;
  const Node type = require(e, "type", item);
  try {
    j.type = joint_type(text(type, item, "type"));
  } catch (const InputError& err) {
    fail(type, item, err.what());
  }
  const Node markers = require(e, "markers", item);
  if (!markers.IsSequence() || markers.size() != 2)
    fail(markers, item, "'markers' must be a list of two marker names" + got(markers));
  std::vector<std::string> names;
  for (const auto& m : model.markers()) names.push_back(m.name);
  int idx[2] = {-1, -1};
  for (int k = 0; k < 2; ++k) {
    const std::string mname = text(markers[k], item, "markers");
    for (std::size_t m = 0; m < names.size(); ++m)
      if (names[m] == mname) idx[k] = static_cast<int>(m);
    if (idx[k] < 0)
      fail(markers[k], item, "no marker named '" + mname + "' (known: " + join(names) + ")");
  }
  j.marker1 = idx[0];
  j.marker2 = idx[1];
  if (const Node len = e["length"]) {
    if (j.type != JointType::distance) fail(len, item, "'length' applies to distance joints only");
    j.length = number_in(len, item, "length", 0.0, 1e300, true);
  }
  try {
    model.add_joint(std::move(j));
  } catch (const InputError& err) {
    rethrow(e, item, err);
  }
}

IntegratorSettings SceneReader::read_integrator(const Node& n) const {
  const std::string item = "integrator";
  std::vector<std::string> keys;
  for (const auto& info : integrator_settings()) keys.push_back(info.key);
  check_keys(n, item, keys);
  IntegratorSettings s;
  // the name first, so that every other key is checked against the same table
  if (n["name"]) s.name = choice(n["name"], item, "name", integrator_names());
  for (auto it = n.begin(); it != n.end(); ++it) {
    const std::string key = it->first.as<std::string>();
    if (key == "name") continue;
    const Node v = it->second;
    if (!v.IsScalar()) fail(v, item, "'" + key + "' must be a single value" + got(v));
    // The value's type in the scene's own words first (range checks follow).
    for (const auto& info : integrator_settings())
      if (info.key == key && info.kind == "number") number(v, item, key);
    try {
      set_integrator_setting(s, key, v.Scalar());
    } catch (const InputError& e) {
      fail(v, item, e.what());
    }
  }
  return s;
}

OutputSpec SceneReader::read_output(const Node& n, const Model& model, double t_start,
                                    double t_end) const {
  const std::string item = "output";
  check_keys(n, item, {"grid", "step", "body", "start", "channels"});
  OutputSpec out;
  if (n["grid"]) out.grid = choice(n["grid"], item, "grid", {"time", "crank-angle"});
  const bool crank = out.grid == "crank-angle";
  if (n["step"]) {
    out.step = number_in(n["step"], item, "step", 0.0, crank ? 360.0 : 1e300, true);
  } else {
    out.step = crank ? 1.0 : (t_end - t_start) / 1000.0;
  }
  if (n["start"]) {
    out.start = number(n["start"], item, "start");
    out.start_given = true;
  } else {
    out.start = t_start;
  }
  if (crank) {
    const Node b = require(n, "body", item);
    out.crank_body = text(b, item, "body");
    int body = -1;
    for (std::size_t k = 0; k < model.bodies().size(); ++k)
      if (model.bodies()[k].name == out.crank_body) body = static_cast<int>(k);
    if (body < 0) fail(b, item, "no body named '" + out.crank_body + "'");
    if (model.bodies()[body].lof.kind() != LofKind::Spin)
      fail(b, item,
           "the crank-angle grid needs a body with a spin LOF; '" + out.crank_body + "' has none");
  } else {
    if (n["body"]) fail(n["body"], item, "'body' applies to the crank-angle grid only");
    if (out.start_given && (out.start < t_start || out.start > t_end))
      fail(n["start"], item, "'start' = " + number_text(out.start) + " s is outside the time span");
  }
  // Output rows before any time is computed: a tiny step (or a huge time span)
  // would allocate without bound.
  {
    double span = t_end - (out.start_given && !crank ? out.start : t_start);
    std::string what = "s of time";
    if (crank) {
      const Lof& lof = model.bodies()[model.find_body(out.crank_body)].lof;
      span = std::abs(lof.spin_angle(t_end) - lof.spin_angle(t_start)) * 180.0 / M_PI;
      what = "deg of crank angle";
    }
    const double rows = span / out.step + 1.0;
    if (!(rows <= kMaxOutputRows))
      fail(n["step"] ? n["step"] : n, item,
           "'step' = " + number_text(out.step) + (crank ? " deg" : " s") + " over " +
               number_text(span) + " " + what + " gives " + number_text(rows) +
               " output rows, more than the limit of " + number_text(kMaxOutputRows) +
               "; use a larger 'step' or a shorter time span");
  }
  if (const Node ch = n["channels"]) {
    if (!ch.IsSequence()) fail(ch, item, "'channels' must be a list");
    check_size(ch, item, "channels", kMaxSceneItems);
    std::map<std::pair<int, std::string>, std::size_t> requested;
    for (std::size_t i = 0; i < ch.size(); ++i) {
      const Node c = ch[i];
      const std::string ci = "output.channels[" + std::to_string(i) + "]";
      check_keys(c, ci, {"marker", "element", "modal"});
      if (c.size() != 1) fail(c, ci, "give exactly one of 'marker', 'element' and 'modal'");
      ChannelRequest req;
      req.line = c.Mark().line + 1;
      std::vector<std::string> names;
      if (c["marker"]) {
        req.kind = ChannelRequest::Kind::Marker;
        req.name = text(c["marker"], ci, "marker");
        for (std::size_t k = 0; k < model.markers().size(); ++k) {
          names.push_back(model.markers()[k].name);
          if (names.back() == req.name) req.index = static_cast<int>(k);
        }
      } else if (c["element"]) {
        req.kind = ChannelRequest::Kind::Element;
        req.name = text(c["element"], ci, "element");
        for (std::size_t k = 0; k < model.elements().size(); ++k) {
          names.push_back(model.elements()[k]->name());
          if (names.back() == req.name) req.index = static_cast<int>(k);
        }
      } else {
        req.kind = ChannelRequest::Kind::Modal;
        req.name = text(c["modal"], ci, "modal");
        for (std::size_t k = 0; k < model.bodies().size(); ++k) {
          names.push_back(model.bodies()[k].name);
          if (names.back() == req.name) req.index = static_cast<int>(k);
        }
      }
      if (req.index < 0) {
        const char* what = req.kind == ChannelRequest::Kind::Marker    ? "marker"
                           : req.kind == ChannelRequest::Kind::Element ? "element"
                                                                       : "body";
        fail(c.begin()->second, ci,
             std::string("no ") + what + " named '" + req.name + "' (known: " + join(names) + ")");
      }
      const auto [at, fresh] =
          requested.emplace(std::make_pair(static_cast<int>(req.kind), req.name), i);
      if (!fresh)
        fail(c, ci,
             "repeats output.channels[" + std::to_string(at->second) + "] (" +
                 c.begin()->first.as<std::string>() + ": " + req.name +
                 "): request each channel once");
      out.channels.push_back(req);
    }
  }
  return out;
}

// Where each YAML document of `text` starts, read by yaml-cpp's parser without
// building nodes. yaml-cpp 0.7's LoadAll never returns on a ',' outside [ ] and
// { } (a flow entry at block level, e.g. a line starting with ','): every
// document it begins there is empty and consumes nothing, so it starts the
// next at the same place until memory runs out (found by fuzz_scene). A
// document that starts where the one before it did is such a place: a syntax
// error at its mark.
std::vector<YAML::Mark> document_starts(const std::string& text) {
  struct Starts : YAML::EventHandler {
    std::vector<YAML::Mark> marks;
    void OnDocumentStart(const YAML::Mark& m) override { marks.push_back(m); }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
  } h;
  std::istringstream is(text);
  YAML::Parser parser(is);
  while (parser.HandleNextDocument(h)) {
    const std::size_t n = h.marks.size();
    if (n >= 2 && h.marks[n - 1].pos == h.marks[n - 2].pos) {
      const YAML::Mark& m = h.marks[n - 1];
      const char c =
          m.pos >= 0 && static_cast<std::size_t>(m.pos) < text.size() ? text[m.pos] : '?';
      throw YAML::ParserException(m, std::string("unexpected '") + c + "'" +
                                         (c == ',' ? " outside [ ] or { }" : "") +
                                         ": the parser cannot go on from here");
    }
  }
  return h.marks;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& path) {
  if (text.size() > kMaxSceneBytes)
    throw InputError(path + ": the scene file is " + std::to_string(text.size()) +
                     " bytes, more than the limit of " + std::to_string(kMaxSceneBytes) +
                     " bytes (16 MiB)");
  Node root;
  try {
    const std::vector<YAML::Mark> docs = document_starts(text);
    if (docs.size() > 1) {
      // The line of the second document's start marker ('---').
      int line = docs[1].line >= 0 ? docs[1].line + 1 : 0;
      std::istringstream is(text);
      int no = 0, starts = 0;
      bool content = false;
      for (std::string l; std::getline(is, l);) {
        ++no;
        if (l.rfind("---", 0) == 0) {
          if (content || ++starts > 1) {
            line = no;
            break;
          }
        } else if (!l.empty() && l[0] != '#' && l[0] != '%' &&
                   l.find_first_not_of(" \t\r") != std::string::npos) {
          content = true;
        }
      }
      throw InputError(path + ":" + std::to_string(line) + ": scene: a second YAML document " +
                       "('---') is not allowed; a scene file holds one document");
    }
    if (!docs.empty()) root = YAML::Load(text);  // the one document
  } catch (const YAML::ParserException& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1) +
                     ": YAML syntax error: " + e.msg);
  }
  SceneReader reader(path, std::filesystem::path(path).parent_path());
  Scene scene;
  try {
    scene = reader.read(root);
  } catch (const YAML::Exception& e) {
    throw InputError(path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  scene.text = text;
  scene.path = path;
  return scene;
}

Scene read_scene(const std::string& path) {
  std::error_code ec;
  const auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st))
    throw InputError(path + ": cannot open the scene file (no such file)");
  if (!std::filesystem::is_regular_file(st))
    throw InputError(path + ": the scene is not a regular file (a folder, device or pipe)");
  const auto bytes = std::filesystem::file_size(path, ec);
  if (!ec && bytes > kMaxSceneBytes)
    throw InputError(path + ": the scene file is " + std::to_string(bytes) +
                     " bytes, more than the limit of " + std::to_string(kMaxSceneBytes) +
                     " bytes (16 MiB)");
  std::ifstream f(path);
  if (!f) throw InputError(path + ": cannot open the scene file");
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_scene(ss.str(), path);
}

}  // namespace evas
