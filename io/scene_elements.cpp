// Scene files (see scene.h): elements, their markers and their parameters,
// read through the element registry (elements/registry.h).
#include <algorithm>
#include <filesystem>

#include "elements/piston_conrod.h"
#include "elements/plausibility.h"
#include "elements/registry.h"
#include "io/scene_reader.h"

namespace evas::scene_detail {

namespace {

std::string speed_text(const SpeedProfile& s) {
  if (s.is_constant()) return format_number(s.speeds()[0]) + " rad/s";
  return "a profile of " + std::to_string(s.times().size()) + " points, " +
         format_number(s.min_speed()) + " .. " + format_number(s.max_speed()) + " rad/s";
}

}  // namespace

// The operating point's speed is stated once, by the crank: the spinning
// body that carries the element's first marker (a piston's crankpin, the
// motor's clutch), or else the one body with a spin LOF. An element that
// prescribes a crank speed and gives none follows that body's profile; one
// that gives its own must agree with it.
const SpeedProfile* SceneReader::connect_crank_speed(Element& el, const Node& e,
                                                     const std::string& item, const Model& model) {
  if (!el.wants_speed() && !el.own_speed()) return nullptr;
  std::vector<const Body*> spins;
  for (const auto& b : model.bodies())
    if (b.lof.kind() == LofKind::Spin) spins.push_back(&b);
  const Body* crank = nullptr;
  const int first = el.markers().empty() ? -1 : model.markers()[el.markers()[0]].body;
  if (first >= 0 && model.bodies()[first].lof.kind() == LofKind::Spin)
    crank = &model.bodies()[first];
  else if (spins.size() == 1)
    crank = spins[0];
  if (el.wants_speed()) {
    if (!crank) {
      std::vector<std::string> names;
      for (const auto* b : spins) names.push_back(b->name);
      fail(e, item,
           spins.empty() ? "parameter 'speed' is required: no body has a spin LOF whose speed "
                           "the element could follow"
                         : "gives no 'speed', its first marker is not on a spinning body, and "
                           "several bodies spin (" +
                               join(names) + "): give the element's 'speed'");
    }
    el.follow_speed(crank->lof.speed_profile());
    return &crank->lof.speed_profile();
  }
  if (!crank) return el.own_speed();
  const SpeedProfile& w = crank->lof.speed_profile();
  if (!el.own_speed()->same_as(w))
    fail(e["speed"] ? e["speed"] : e, item,
         "speed " + speed_text(*el.own_speed()) + " disagrees with body '" + crank->name +
             "' (its spin LOF turns at " + speed_text(w) +
             "); omit the element's 'speed' to follow the crank");
  return el.own_speed();
}

// A firing cylinder (a pressure table or map over crank angle) on a crank at
// rest or turning backwards holds its piston at one angle under a constant gas
// load, or reads the table backwards: an error, not a run.
void SceneReader::check_firing_speed(const SpeedProfile* w, const Node& e, const std::string& item,
                                     const ParamValues& values) const {
  const bool fires = (values.texts.count("pressure_file") && values.given("pressure_file")) ||
                     (values.texts.count("pressure_map") && values.given("pressure_map"));
  if (!fires || !w || w->min_speed() > 0.0) return;
  if (w->max_speed() > 0.0) {
    warnings_.push_back(file_ + ":" + std::to_string(e.Mark().line + 1) + ": " + item +
                        ": the cylinder fires but the crank's speed profile reaches " +
                        format_number(w->min_speed()) +
                        " rad/s: while the crank is at rest or turns backwards the piston "
                        "sits under the gas load of one crank angle");
    return;
  }
  fail(e["speed"] ? e["speed"] : e, item,
       "the cylinder fires (" +
           std::string(values.given("pressure_file") ? "pressure_file" : "pressure_map") +
           ") but the crank turns at " + speed_text(*w) +
           ": a firing engine needs a positive crank speed (a crank at rest holds the piston at "
           "one angle under a constant gas load); speeds are in rad/s, 3000 rpm is 314.159 "
           "rad/s");
}

// The operating point's load is stated once, in the scene's operating_point
// (read before the elements): an element whose data need it (a pressure map
// with a load column) takes it, and one that needs it without a load given is
// refused, naming the element and what reads the load.
void SceneReader::connect_operating_load(Element& el, const Node& e, const std::string& item) {
  const std::string source = el.load_source();
  if (source.empty()) return;
  if (!load_)
    fail(e, item,
         "its " + source +
             " has a load column, but the scene gives no operating_point.load: add "
             "'operating_point: {load: L}' (the load at which the map is read)");
  el.set_operating_load(*load_);
  load_read_ = true;
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
    const std::string at = file_ + ":" + std::to_string(e.Mark().line + 1) + ": " + item;
    complete_params(*type, values, at);
    check_plausible(*type, values, at, warnings_);
    std::unique_ptr<Element> element = type->make(name, idx, values);
    if (const std::string why = element->run_refusal(); !why.empty())
      throw InputError(at + ": " + why);
    const SpeedProfile* speed = connect_crank_speed(*element, e, item, model);
    if (type->type == "piston-conrod") {
      check_firing_speed(speed, e, item, values);
      const double peak = static_cast<const PistonConrod&>(*element).peak_gas_pressure();
      const std::string table = values.given("pressure_map")
                                    ? "map '" + values.text("pressure_map") + "'"
                                    : "table '" + values.text("pressure_file") + "'";
      if (peak > 0.0)
        if (std::string w = peak_pressure_warning(peak, table); !w.empty())
          warnings_.push_back(at + ": " + w);
    }
    connect_operating_load(*element, e, item);
    model.add_element(std::move(element));
  } catch (const InputError& err) {
    const std::string msg = err.what();
    if (msg.rfind(file_ + ":", 0) == 0) throw;
    rethrow(e, item, err);
  }
}

}  // namespace evas::scene_detail
