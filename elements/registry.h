// Element types, each declared once: its parameters with units, defaults and
// valid ranges, the number of markers, and a factory. The scene reader, input
// validation and the documentation (`evas elements`) all read this table.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "model/element.h"

namespace evas {

struct ParamSpec {
  enum class Kind { Scalar, Vector3, List, Text };
  std::string key;
  Kind kind = Kind::Scalar;
  std::string unit;
  std::string doc;
  bool required = false;
  std::vector<double> default_value;  ///< used when not required and absent
  double min = -1e300, max = 1e300;   ///< valid range of every component
  std::vector<std::string> choices;   ///< Text: allowed values (empty = any)
  std::string default_text;
  bool is_path = false;  ///< Text naming a file: relative paths are relative to the scene file
};

/// Validated parameter values of one element instance.
struct ParamValues {
  std::map<std::string, std::vector<double>> numbers;
  std::map<std::string, std::string> texts;
  double scalar(const std::string& key) const { return numbers.at(key).at(0); }
  Vec3 vec3(const std::string& key) const;
  const std::vector<double>& list(const std::string& key) const { return numbers.at(key); }
  const std::string& text(const std::string& key) const { return texts.at(key); }
  bool has(const std::string& key) const { return numbers.count(key) || texts.count(key); }
  /// True if the value was given (not filled in by complete_params from the default).
  bool given(const std::string& key) const { return has(key) && !defaulted.count(key); }
  std::set<std::string> defaulted;  ///< keys filled from their defaults
};

struct ElementType {
  std::string type;
  std::string doc;
  int num_markers = 2;  ///< exact marker count; 0 = two or more (checked by the factory)
  std::vector<ParamSpec> params;
  /// Builds the element; `where` names the element for error messages.
  std::function<std::unique_ptr<Element>(const std::string& name, const std::vector<int>& markers,
                                         const ParamValues& values)>
      make;
};

/// Parameter declarations shared by every element type. `required` parameters
/// have no default; components must lie in [min, max].
ParamSpec scalar_param(const std::string& key, const std::string& unit, const std::string& doc,
                       bool required, double def, double min = -1e300, double max = 1e300);
ParamSpec vector_param(const std::string& key, ParamSpec::Kind kind, const std::string& unit,
                       const std::string& doc, std::vector<double> def, double min = -1e300,
                       bool required = false);
ParamSpec text_param(const std::string& key, const std::string& doc,
                     std::vector<std::string> choices, const std::string& def);

/// All element types, in documentation order.
const std::vector<ElementType>& element_types();
/// Throws InputError listing the known types when `type` is unknown.
const ElementType& element_type(const std::string& type);
/// Checks one value against its spec; throws InputError("<where>: parameter '<key>' ...").
void check_param(const ParamSpec& spec, const std::vector<double>& value, const std::string& where);
/// Fills defaults and checks required keys; throws InputError naming `where` and the key.
void complete_params(const ElementType& type, ParamValues& values, const std::string& where);
/// Markdown table of every element type and its parameters.
std::string element_reference_markdown();

}  // namespace evas
