#include "elements/registry.h"

#include <cmath>
#include <sstream>

#include "elements/belt.h"
#include "elements/engine_mount.h"
#include "elements/journal_bearing.h"
#include "elements/motor.h"
#include "elements/piston_conrod.h"
#include "elements/plausibility.h"
#include "elements/spring_damper.h"
#include "elements/thrust_bearing.h"

namespace evas {

Vec3 ParamValues::vec3(const std::string& key) const {
  const auto& v = numbers.at(key);
  return Vec3(v.at(0), v.at(1), v.at(2));
}

ParamSpec scalar_param(const std::string& key, const std::string& unit, const std::string& doc,
                       bool required, double def, double min, double max) {
  ParamSpec p;
  p.key = key;
  p.kind = ParamSpec::Kind::Scalar;
  p.unit = unit;
  p.doc = doc;
  p.required = required;
  if (!required) p.default_value = {def};
  p.min = min;
  p.max = max;
  return p;
}

ParamSpec vector_param(const std::string& key, ParamSpec::Kind kind, const std::string& unit,
                       const std::string& doc, std::vector<double> def, double min, bool required) {
  ParamSpec p;
  p.key = key;
  p.kind = kind;
  p.unit = unit;
  p.doc = doc;
  p.default_value = std::move(def);
  p.required = required;
  p.min = min;
  return p;
}

ParamSpec text_param(const std::string& key, const std::string& doc,
                     std::vector<std::string> choices, const std::string& def) {
  ParamSpec p;
  p.key = key;
  p.kind = ParamSpec::Kind::Text;
  p.doc = doc;
  p.choices = std::move(choices);
  p.default_text = def;
  return p;
}

namespace {

ParamSpec vec3_param(const std::string& key, const std::string& unit, const std::string& doc,
                     double min = -1e300) {
  return vector_param(key, ParamSpec::Kind::Vector3, unit, doc, {0.0, 0.0, 0.0}, min);
}

std::vector<ElementType> make_types() {
  std::vector<ElementType> types;
  {
    ElementType t;
    t.type = "spring-damper";
    t.doc =
        "Linear spring-damper between two markers, translation and rotation, in marker 1's "
        "axes. Load on marker 2: F = -(k d + c dv) - preload with d = R1^T (p2 - p1) - length; "
        "M = -(kr r + cr dw) with r = R1^T (psi2 - psi1).";
    t.num_markers = 2;
    t.params = {vec3_param("stiffness", "N/m", "translational stiffness per axis", 0.0),
                vec3_param("damping", "N s/m", "translational damping per axis", 0.0),
                vec3_param("rot_stiffness", "N m/rad", "rotational stiffness per axis", 0.0),
                vec3_param("rot_damping", "N m s/rad", "rotational damping per axis", 0.0),
                vec3_param("length", "m", "free length vector (marker 1 axes)"),
                vec3_param("preload", "N", "constant force subtracted from the load on marker 2")};
    t.make = [](const std::string& name, const std::vector<int>& markers, const ParamValues& v) {
      return std::make_unique<SpringDamper>(name, markers, v.vec3("stiffness"), v.vec3("damping"),
                                            v.vec3("rot_stiffness"), v.vec3("rot_damping"),
                                            v.vec3("length"), v.vec3("preload"));
    };
    types.push_back(std::move(t));
  }
  types.push_back(journal_bearing_element_type());
  types.push_back(piston_conrod_element_type());
  types.push_back(motor_element_type());
  types.push_back(engine_mount_element_type());
  types.push_back(thrust_bearing_element_type());
  types.push_back(belt_element_type());
  return types;
}

std::string kind_name(ParamSpec::Kind k) {
  switch (k) {
    case ParamSpec::Kind::Scalar:
      return "number";
    case ParamSpec::Kind::Vector3:
      return "3-vector";
    case ParamSpec::Kind::List:
      return "list";
    case ParamSpec::Kind::Text:
      return "text";
  }
  return "?";
}

}  // namespace

const std::vector<ElementType>& element_types() {
  static const std::vector<ElementType> types = make_types();
  return types;
}

const ElementType& element_type(const std::string& type) {
  std::string known;
  for (const auto& t : element_types()) {
    if (t.type == type) return t;
    known += (known.empty() ? "" : ", ") + t.type;
  }
  throw InputError("unknown element type '" + type + "' (known: " + known + ")");
}

void check_param(const ParamSpec& spec, const std::vector<double>& value,
                 const std::string& where) {
  const std::string head = where + ": parameter '" + spec.key + "'";
  if (spec.kind == ParamSpec::Kind::Scalar && value.size() != 1)
    throw InputError(head + " must be a single number, got " + std::to_string(value.size()) +
                     " values");
  if (spec.kind == ParamSpec::Kind::Vector3 && value.size() != 3)
    throw InputError(head + " must have 3 values, got " + std::to_string(value.size()));
  if (spec.kind == ParamSpec::Kind::List && value.empty())
    throw InputError(head + " must not be empty");
  for (double x : value) {
    if (!std::isfinite(x)) throw InputError(head + " must be finite");
    if (x < spec.min || x > spec.max) {
      std::ostringstream os;
      os << head << " = " << x << " is outside [" << spec.min << ", " << spec.max << "]"
         << (spec.unit.empty() ? "" : " " + spec.unit);
      throw InputError(os.str());
    }
  }
}

void complete_params(const ElementType& type, ParamValues& values, const std::string& where) {
  for (const auto& p : type.params) {
    if (values.has(p.key)) continue;
    if (p.required) throw InputError(where + ": missing required parameter '" + p.key + "'");
    values.defaulted.insert(p.key);
    if (p.kind == ParamSpec::Kind::Text)
      values.texts[p.key] = p.default_text;
    else
      values.numbers[p.key] = p.default_value;
  }
}

std::string element_reference_markdown() {
  std::ostringstream os;
  for (const auto& t : element_types()) {
    os << "### `" << t.type << "` ("
       << (t.num_markers > 0 ? std::to_string(t.num_markers) : std::string("two or more"))
       << " markers)\n\n"
       << t.doc << "\n\n";
    os << "| parameter | kind | unit | default | range | plausible | meaning |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const auto& p : t.params) {
      std::ostringstream def;
      if (p.required) {
        def << "required";
      } else if (p.kind == ParamSpec::Kind::Text) {
        def << p.default_text;
      } else {
        for (std::size_t i = 0; i < p.default_value.size(); ++i)
          def << (i ? ", " : "") << p.default_value[i];
      }
      std::ostringstream range;
      if (!p.choices.empty()) {
        for (std::size_t i = 0; i < p.choices.size(); ++i)
          range << (i ? " / " : "") << p.choices[i];
      } else if (p.kind == ParamSpec::Kind::Text) {
        range << (p.is_path ? "file path" : "text");
      } else {
        auto bound = [&](double x, const char* inf) {
          if (std::abs(x) < 1e299)
            range << x;
          else
            range << inf;
        };
        bound(p.min, "-inf");
        range << " .. ";
        bound(p.max, "inf");
      }
      const PlausibleRange* pr = plausible_range(t.type, p.key);
      os << "| `" << p.key << "` | " << kind_name(p.kind) << " | " << p.unit << " | " << def.str()
         << " | " << range.str() << " | " << (pr ? plausible_text(*pr) : "") << " | " << p.doc
         << " |\n";
    }
    os << "\n";
  }
  return os.str();
}

}  // namespace evas
