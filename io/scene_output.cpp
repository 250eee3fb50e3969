// Scene files (see scene.h): the integrator block (integrators/settings.h)
// and the output spec (grid, step, start, channels).
#include <algorithm>
#include <cmath>
#include <map>

#include "integrators/settings.h"
#include "io/outputs.h"
#include "io/scene_reader.h"

namespace evas::scene_detail {

IntegratorSettings SceneReader::read_integrator(const Node& n) const {
  const std::string item = "integrator";
  std::vector<std::string> keys;
  for (const auto& info : integrator_settings()) keys.push_back(info.key);
  for (const auto& [name, d] : declared_settings()) keys.push_back(d.key);  // plug-ins' own
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
    // the grid's rows are the times the crank passes whole steps: over the
    // run its angle must keep moving one way, so the speed may start from
    // standstill but neither reach zero later nor change sign (a profile stays
    // between its knots, so the knots inside the run and its two ends decide)
    const SpeedProfile& sp = model.bodies()[body].lof.speed_profile();
    const double w_end = sp.speed(t_end);
    double lo = std::min(sp.speed(t_start), w_end), hi = std::max(sp.speed(t_start), w_end);
    bool zero_later = w_end == 0.0;
    for (double k : sp.times()) {
      if (!(k > t_start && k < t_end)) continue;
      const double w = sp.speed(k);
      lo = std::min(lo, w);
      hi = std::max(hi, w);
      zero_later = zero_later || w == 0.0;
    }
    if ((lo < 0.0 && hi > 0.0) || zero_later)
      fail(b, item,
           "the crank-angle grid needs a crank that keeps turning one way; body '" +
               out.crank_body + "' turns at " + number_text(lo) + " .. " + number_text(hi) +
               " rad/s between t = " + number_text(t_start) + " and " + number_text(t_end) + " s" +
               (zero_later ? ", down to standstill" : "") + " (use grid: time)");
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
      if (c.IsMap() && c["surface"]) {
        out.channels.push_back(read_surface(c, ci, model));
        const auto [at, fresh] =
            requested.emplace(std::make_pair(static_cast<int>(ChannelRequest::Kind::Surface),
                                             out.channels.back().name),
                              i);
        if (!fresh)
          fail(c, ci,
               "repeats the name of output.channels[" + std::to_string(at->second) + "] ('" +
                   out.channels.back().name + "'): give each surface request its own 'name'");
        continue;
      }
      check_keys(c, ci,
                 {"marker", "element", "modal", "torsion", "quantities", "frame", "name", "axis"});
      if (c["torsion"]) {
        out.channels.push_back(read_torsion(c, ci, model));
        const auto [at, fresh] =
            requested.emplace(std::make_pair(static_cast<int>(ChannelRequest::Kind::Torsion),
                                             out.channels.back().name),
                              i);
        if (!fresh)
          fail(c, ci,
               "repeats the name of output.channels[" + std::to_string(at->second) + "] ('" +
                   out.channels.back().name + "'): give each torsion request its own 'name'");
        continue;
      }
      if (c["name"] || c["axis"])
        fail(c, ci, "'name' and 'axis' belong to a torsion request ({torsion: [A, B], ...})");
      const std::size_t extra = (c["quantities"] ? 1 : 0) + (c["frame"] ? 1 : 0);
      if (extra && !c["marker"])
        fail(c, ci, "'quantities' and 'frame' belong to a marker request ({marker: NAME, ...})");
      if (c.size() != 1 + extra)
        fail(c, ci, "give exactly one of 'marker', 'element', 'modal', 'torsion' and 'surface'");
      ChannelRequest req;
      req.line = c.Mark().line + 1;
      std::vector<std::string> names;
      if (c["marker"]) {
        req.kind = ChannelRequest::Kind::Marker;
        req.name = text(c["marker"], ci, "marker");
        if (const Node qs = c["quantities"]) {
          if (!qs.IsSequence() || qs.size() == 0)
            fail(qs, ci,
                 "'quantities' must be a list of position, velocity, acceleration, "
                 "angular_velocity, angular_acceleration");
          req.quantities = 0;
          const std::vector<std::pair<std::string, unsigned>> known = {
              {"position", ChannelRequest::kPosition},
              {"velocity", ChannelRequest::kVelocity},
              {"acceleration", ChannelRequest::kAcceleration},
              {"angular_velocity", ChannelRequest::kAngularVelocity},
              {"angular_acceleration", ChannelRequest::kAngularAcceleration}};
          for (const Node& q : qs) {
            const std::string w = text(q, ci, "quantities");
            unsigned bit = 0;
            for (const auto& [word, b] : known)
              if (word == w) bit = b;
            if (!bit)
              fail(q, ci,
                   "unknown quantity '" + w +
                       "' (known: position, velocity, acceleration, angular_velocity, "
                       "angular_acceleration)");
            if (req.quantities & bit) fail(q, ci, "quantity '" + w + "' is given twice");
            req.quantities |= bit;
          }
        }
        if (const Node fr = c["frame"])
          req.local = choice(fr, ci, "frame", {"ground", "marker"}) == "marker";
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
      // a marker may be asked for once in ground and once in its own axes
      const auto [at, fresh] =
          requested.emplace(std::make_pair(static_cast<int>(req.kind),
                                           req.name + (req.local ? " (marker axes)" : "")),
                            i);
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

ChannelRequest SceneReader::read_torsion(const Node& c, const std::string& ci,
                                         const Model& model) const {
  check_keys(c, ci, {"torsion", "name", "axis"});
  const Node t = c["torsion"];
  if (!t.IsSequence() || t.size() != 2)
    fail(t, ci, "'torsion' must list two markers on one body: [A, B] (the twist is B minus A)");
  ChannelRequest req;
  req.kind = ChannelRequest::Kind::Torsion;
  req.line = c.Mark().line + 1;
  std::vector<std::string> names;
  for (const auto& m : model.markers()) names.push_back(m.name);
  int idx[2] = {-1, -1};
  std::string label[2];
  for (int k = 0; k < 2; ++k) {
    label[k] = text(t[k], ci, "torsion");
    for (std::size_t j = 0; j < names.size(); ++j)
      if (names[j] == label[k]) idx[k] = static_cast<int>(j);
    if (idx[k] < 0)
      fail(t[k], ci, "no marker named '" + label[k] + "' (known: " + join(names) + ")");
    const Marker& m = model.markers()[idx[k]];
    if (m.on_ground())
      fail(
          t[k], ci,
          "marker '" + label[k] + "' is on the ground: a twist is between two markers of one body");
    if (!m.has_rotation)
      fail(t[k], ci,
           "marker '" + label[k] +
               "' has no rotation (a single node or a collinear set): the twist needs a set "
               "marker whose nodes span a plane");
  }
  if (idx[0] == idx[1]) fail(t, ci, "the two markers are the same ('" + label[0] + "')");
  const Marker &a = model.markers()[idx[0]], &b = model.markers()[idx[1]];
  if (a.body != b.body)
    fail(t, ci,
         "markers '" + label[0] + "' and '" + label[1] + "' are on different bodies ('" +
             model.bodies()[a.body].name + "', '" + model.bodies()[b.body].name +
             "'): a twist is measured within one body");
  req.index = idx[0];
  req.index2 = idx[1];
  req.name = c["name"] ? text(c["name"], ci, "name") : "twist_" + label[0] + "_" + label[1];
  if (req.name.empty() || req.name.find_first_of(" .,\t") != std::string::npos)
    fail(c["name"] ? c["name"] : c, ci,
         c["name"] ? "'name' must be a word without spaces, dots or commas"
                   : "the default name '" + req.name +
                         "' (from the marker names) is not a word without spaces, dots or "
                         "commas: give 'name'");
  const Body& body = model.bodies()[a.body];
  if (const Node ax = c["axis"]) {
    req.axis = vec3(ax, ci, "axis");
    if (!(req.axis.norm() > 0.0)) fail(ax, ci, "'axis' must not be zero");
    req.axis.normalize();
  } else if (body.lof.kind() == LofKind::Spin) {
    // the spin axis in the body's axes (the spin leaves it where it is)
    req.axis = (body.lof.at(0.0).R_GL.transpose() * body.lof.axis()).normalized();
  } else {
    fail(c, ci,
         "body '" + body.name +
             "' has no spin LOF to take the twist axis from: give 'axis' (in the body's axes)");
  }
  return req;
}

}  // namespace evas::scene_detail

namespace evas::scene_detail {

ChannelRequest SceneReader::read_surface(const Node& c, const std::string& ci,
                                         const Model& model) const {
  check_keys(c, ci, {"surface", "body", "name", "rho_c", "normal", "area", "areas", "per_node"});
  ChannelRequest req;
  req.kind = ChannelRequest::Kind::Surface;
  req.line = c.Mark().line + 1;
  req.set = text(c["surface"], ci, "surface");
  const std::string bname = text(require(c, "body", ci), ci, "body");
  std::vector<std::string> names;
  for (std::size_t k = 0; k < model.bodies().size(); ++k) {
    names.push_back(model.bodies()[k].name);
    if (names.back() == bname) req.index = static_cast<int>(k);
  }
  if (req.index < 0)
    fail(c["body"], ci, "no body named '" + bname + "' (known: " + join(names) + ")");
  const ModalBody& body = *model.bodies()[req.index].data;
  const auto set = body.node_sets.find(req.set);
  if (set == body.node_sets.end()) {
    std::vector<std::string> sets;
    for (const auto& [name, ids] : body.node_sets) sets.push_back(name);
    fail(c["surface"], ci,
         body.label() + " has no node set '" + req.set +
             "' (known: " + (sets.empty() ? std::string("none") : join(sets)) + ")");
  }
  req.name = c["name"] ? text(c["name"], ci, "name") : req.set;
  if (req.name.empty() || req.name.find_first_of(" .,\t") != std::string::npos)
    fail(c["name"] ? c["name"] : c["surface"], ci,
         c["name"] ? "'name' must be a word without spaces, dots or commas"
                   : "the default name '" + req.name +
                         "' (the set's) is not a word without spaces, dots or commas: give "
                         "'name'");
  if (c["rho_c"]) req.rho_c = number_in(c["rho_c"], ci, "rho_c", 0.0, 1e7, true);
  if (c["per_node"]) req.per_node = boolean(c["per_node"], ci, "per_node");
  const auto stored = body.surfaces.find(req.set);
  const bool given = c["normal"] || c["area"] || c["areas"];
  if (stored != body.surfaces.end()) {
    if (given)
      fail(c, ci,
           body.label() + " holds the areas and normals of set '" + req.set +
               "' from its FE mesh: leave out 'normal', 'area' and 'areas'");
    req.surface = std::make_shared<const SurfaceSet>(stored->second);
  } else {
    if (!c["normal"] || (!c["area"] && !c["areas"])) {
      std::vector<std::string> with;
      for (const auto& [name, s] : body.surfaces) with.push_back(name);
      fail(c, ci,
           body.label() + " holds no areas and normals for set '" + req.set +
               "' (it holds them for: " + (with.empty() ? std::string("no set") : join(with)) +
               "; `evas modal build` stores them for every set of mesh faces): give 'normal' "
               "(the outward normal, in the body's axes) and 'area' (the set's total area "
               "[m^2], shared equally by its nodes) or 'areas' (one per node [m^2])");
    }
    if (c["area"] && c["areas"]) fail(c, ci, "give 'area' or 'areas', not both");
    auto s = std::make_shared<SurfaceSet>();
    s->nodes = set->second;
    const auto n = static_cast<Eigen::Index>(s->nodes.size());
    Vec3 nn = vec3(c["normal"], ci, "normal");
    if (!(nn.norm() > 0.0)) fail(c["normal"], ci, "'normal' must not be zero");
    nn.normalize();
    s->normal.resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) s->normal.row(i) = nn.transpose();
    if (c["area"]) {
      const double a = number_in(c["area"], ci, "area", 0.0, 1e6, true);
      s->area = Vec::Constant(n, a / static_cast<double>(n));
    } else {
      const Node as = c["areas"];
      if (!as.IsSequence() || static_cast<Eigen::Index>(as.size()) != n)
        fail(as, ci,
             "'areas' must list one area [m^2] per node of set '" + req.set + "' (" +
                 std::to_string(n) + " nodes)");
      s->area.resize(n);
      for (Eigen::Index i = 0; i < n; ++i)
        s->area[i] = number_in(as[static_cast<std::size_t>(i)], ci, "areas", 0.0, 1e6);
      if (!(s->area.sum() > 0.0)) fail(as, ci, "'areas' sum to 0");
    }
    req.surface = std::move(s);
  }
  if (req.per_node && req.surface->nodes.size() > 5000)
    fail(c["per_node"], ci,
         "set '" + req.set + "' has " + std::to_string(req.surface->nodes.size()) +
             " nodes: per_node writes one channel per node, at most 5000");
  return req;
}

}  // namespace evas::scene_detail
