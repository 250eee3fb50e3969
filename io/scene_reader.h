// Private to io/ (included by io/scene*.cpp only): the reader of one scene
// document and the checks it shares. Each part of the file is read in its own
// source: the document, time span and YAML syntax in scene.cpp, bodies (body
// files, generated bodies, modes, LOFs) in scene_bodies.cpp, markers and joints
// in scene_markers.cpp, elements in scene_elements.cpp, the integrator block and
// output spec in scene_output.cpp. The format is described in io/scene.h.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "bodies/cylinder_fit.h"
#include "elements/registry.h"
#include "io/scene.h"

namespace evas::scene_detail {

using Node = YAML::Node;

// Limits checked before allocating or iterating: a scene file larger than
// this is refused before yaml-cpp parses it; lists longer than these are
// refused before they are walked.
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;  // 16 MiB
constexpr std::size_t kMaxSceneItems = 100000;        // bodies, markers, elements, channels
constexpr std::size_t kMaxListEntries = 1000000;      // numbers: node ids, weights, tables

/// The entries of `v` separated by ", " (for "known: ..." lists).
std::string join(const std::vector<std::string>& v);
/// `x` as an ostream writes it by default (6 significant digits).
std::string number_text(double x);

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
  /// modes: damping_above: {frequency: F, ratio: Z}: modal damping 2 Z omega for
  /// every elastic mode above F Hz (docs/scenes.md).
  void damp_above(const Node& node, const std::string& mi, ModalBody& body);
  /// Body::quasi_static from `modes: {quasi_static_above: HZ}`: the elastic
  /// modes above HZ (each must be damped).
  void set_quasi_static(const Node& node, const std::string& mi, Body& body);
  ModalBody truncate(ModalBody body, const Node& modes, const std::string& item) const;
  Lof read_lof(const Node& l, const std::string& item) const;
  void read_marker(const Node& m, std::size_t i, Model& model);
  void read_element(const Node& e, std::size_t i, Model& model);
  /// The speed profile the element prescribes (its own or the crank's), or null.
  const SpeedProfile* connect_crank_speed(Element& el, const Node& e, const std::string& item,
                                          const Model& model);
  void connect_operating_load(Element& el, const Node& e, const std::string& item);
  void check_firing_speed(const SpeedProfile* w, const Node& e, const std::string& item,
                          const ParamValues& values) const;
  void read_joint(const Node& e, std::size_t i, Model& model);
  IntegratorSettings read_integrator(const Node& n) const;
  /// An output request {torsion: [A, B], name: N, axis: [x, y, z]} (io/outputs.h).
  ChannelRequest read_torsion(const Node& c, const std::string& ci, const Model& model) const;
  /// An output request {surface: SET, body: B, name: N, rho_c: Z, normal: [..],
  /// area: A | areas: [..], per_node: bool} (model/surface.h).
  ChannelRequest read_surface(const Node& c, const std::string& ci, const Model& model) const;
  OutputSpec read_output(const Node& n, const Model& model, double t_start, double t_end) const;

  std::string file_;
  std::filesystem::path dir_;
  // operating_point.load (stated once in the scene), its node for errors, and
  // whether an element read it
  std::optional<double> load_;
  Node load_node_;
  bool load_read_ = false;
  // plausibility warnings, for Scene::warnings (read_lof is const)
  mutable std::vector<std::string> warnings_;
};

}  // namespace evas::scene_detail
