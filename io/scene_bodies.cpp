// Scene files (see scene.h): bodies, from a body file (modal contract check,
// truncation of modes, damping) or generated (truss beam), and their LOFs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "bodies/body_builder.h"
#include "bodies/modal_contract.h"
#include "bodies/truss.h"
#include "elements/plausibility.h"
#include "io/body_cache.h"
#include "io/body_file.h"
#include "io/scene_reader.h"

namespace evas::scene_detail {

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
  if (modes)
    check_keys(modes, item + " modes",
               {"rigid", "elastic", "max_frequency", "quasi_static_above", "damping_above"});
  if (modes && modes["damping_above"] && gen)
    fail(modes["damping_above"], item + " modes",
         "'damping_above' applies to body files ('file') only");

  std::shared_ptr<const ModalBody> data;
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
    // everything the body made of the file depends on besides the file
    YAML::Emitter modes_text;
    if (modes) modes_text << modes;
    // numbers to the last bit (number_text rounds to 6 digits): two damping
    // ratios or tolerances that differ are two recipes
    auto exact = [](double x) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%a", x);
      return std::string(buf);
    };
    const std::string recipe = name + "\n" + modes_text.c_str() + "\n" +
                               (zeta_node ? exact(zeta) : "-") + "\n" + exact(tolerance);
    auto derive = [&](ModalBody body) {
      // The modal contract (orthonormal modes, rigid modes rigid, ...) of the
      // file as written, before any truncation.
      const ModalContract contract = check_modal_contract(body, tolerance);
      if (const ModalCheck* f = contract.first_failure())
        fail(
            file, item,
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
      if (modes && modes["damping_above"])
        damp_above(modes["damping_above"], item + " modes", body);
      body.validate();  // once per cached body, not once per parse
      return body;
    };
    try {
      data = derived_body_cached(p.string(), recipe, derive);
    } catch (const InputError& e) {
      const std::string msg = e.what();
      if (msg.rfind(file_ + ":", 0) == 0) throw;  // said with its place already
      fail(file, item, msg);
    }
  }
  if (data->num_modes() == 0) fail(modes ? modes : b, item, "no modes left after truncation");

  const Node lof_node = b["lof"];
  const Lof lof =
      lof_node ? read_lof(lof_node, item + " lof") : Lof::fixed(Vec3::Zero(), Mat3::Identity());
  int index = -1;
  try {
    index = model.add_body(name, data, lof, /*checked=*/!gen);
  } catch (const InputError& e) {
    rethrow(b, item, e);
  }
  if (modes && modes["quasi_static_above"])
    set_quasi_static(modes["quasi_static_above"], item + " modes", model.bodies()[index]);
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

void SceneReader::damp_above(const Node& node, const std::string& mi, ModalBody& body) {
  const std::string it = mi + " damping_above";
  expect_map(node, it);
  check_keys(node, it, {"frequency", "ratio"});
  const double f0 = number_in(require(node, "frequency", it), it, "frequency", 0.0, 1e300, true);
  const double zeta = number_in(require(node, "ratio", it), it, "ratio", 0.0, 10.0);
  for (int k = 0; k < body.num_modes(); ++k) {
    if (body.kinds[k] != ModeKind::Elastic) continue;
    const double w = std::sqrt(std::max(0.0, body.eigenvalues[k]));
    if (w / (2.0 * M_PI) > f0) body.damping[k] = 2.0 * zeta * w;
  }
}

void SceneReader::set_quasi_static(const Node& node, const std::string& mi, Body& body) {
  const double above = number_in(node, mi, "quasi_static_above", 0.0, 1e300, true);
  const ModalBody& d = *body.data;
  body.quasi_static.clear();
  for (int k = 0; k < d.num_modes(); ++k) {
    if (d.kinds[k] != ModeKind::Elastic) continue;
    const double f = std::sqrt(std::max(0.0, d.eigenvalues[k])) / (2.0 * M_PI);
    if (!(f > above)) continue;
    if (!(d.damping[k] > 0.0))
      fail(node, mi,
           "mode " + std::to_string(k) + " (" + number_text(f) +
               " Hz) would be quasi-static but has no modal damping: give the body a "
               "damping_ratio > 0 (without damping a quasi-static mode's velocity is of index 2)");
    body.quasi_static.push_back(k);
  }
  if (body.quasi_static.empty())
    warnings_.push_back(file_ + ":" + std::to_string(node.Mark().line + 1) + ": " + mi +
                        ": no elastic mode above quasi_static_above = " + number_text(above) +
                        " Hz; every mode stays dynamic");
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
  // unit slips (elements/plausibility.h): mm for m, MPa for Pa, g/cm^3 for kg/m^3
  for (const auto& [key, x] : {std::pair<const char*, double>{"length", spec.length},
                               {"width", spec.width},
                               {"youngs", spec.youngs},
                               {"area", spec.area},
                               {"density", spec.density}})
    if (g[key])
      if (std::string w = plausibility_warning(*plausible_range("generate", key), x); !w.empty())
        warnings_.push_back(file_ + ":" + std::to_string(g[key].Mark().line + 1) + ": " + it +
                            ": " + w);

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
      // a speed in rpm typed for rad/s: warned once per LOF (elements/plausibility.h)
      for (double w : speeds)
        if (std::string warn = plausibility_warning(*plausible_range("lof", "speed"), w);
            !warn.empty()) {
          const Node at = speed ? speed : profile;
          warnings_.push_back(file_ + ":" + std::to_string(at.Mark().line + 1) + ": " + item +
                              ": " + warn);
          break;
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

}  // namespace evas::scene_detail
