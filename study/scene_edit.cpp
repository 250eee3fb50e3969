// Scene overrides (scene_edit.h).
#include "study/scene_edit.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>

#include "study/case_grid.h"

namespace evas::study {

namespace {

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// Sets the dotted `path` below `item` to a fresh copy of `value`.
void set_path(YAML::Node item, const std::vector<std::string>& path, const std::string& value) {
  YAML::Node node = item;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    YAML::Node next = node[path[i]];
    if (!next || !next.IsMap()) {
      node[path[i]] = YAML::Node(YAML::NodeType::Map);
      next = node[path[i]];
    }
    node.reset(next);
  }
  node[path.back()] = YAML::Load(value);
  // keys that stand for each other: setting one replaces the other, so that
  // `--param crank.lof.speed_profile=[[0, 104.7], [2, 418.9]]` turns a constant
  // speed into a run-up (and `...speed=...` a run-up into a constant speed), and
  // `--param 'cyl*.pressure_map=MAP'` a piston's one table into a map over speed
  static const std::pair<const char*, const char*> alternatives[] = {
      {"speed", "speed_profile"}, {"pressure_file", "pressure_map"}};
  for (const auto& [a, b] : alternatives) {
    if (path.back() == a && node[b]) node.remove(b);
    if (path.back() == b && node[a]) node.remove(a);
  }
}

}  // namespace

std::string edit_scene_text(const std::string& text, const std::vector<std::string>& params,
                            const std::string& option) {
  if (params.empty()) return text;
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(option + ": the scene is not valid YAML: " + e.what());
  }
  if (!root.IsMap()) throw InputError(option + ": the scene is not a YAML mapping");
  for (const std::string& a : params) {
    const std::string where = option + " '" + a + "'";
    const auto eq = a.find('=');
    if (eq == std::string::npos) throw InputError(where + ": expected ITEM.KEY=VALUE");
    const std::string lhs = a.substr(0, eq), value = a.substr(eq + 1);
    std::vector<std::string> path;
    std::stringstream ss(lhs);
    for (std::string part; std::getline(ss, part, '.');) path.push_back(part);
    if (path.size() < 2 || lhs.back() == '.')
      throw InputError(where +
                       ": expected ITEM.KEY=VALUE (ITEM a body, marker or element "
                       "name, or time, integrator, output, operating_point)");
    for (const auto& p : path)
      if (p.empty()) throw InputError(where + ": empty name in '" + lhs + "'");
    if (value.empty()) throw InputError(where + ": empty value");
    try {
      YAML::Load(value);
    } catch (const YAML::Exception& e) {
      throw InputError(where + ": the value is not valid YAML: " + e.what());
    }
    const std::string item = path.front();
    const std::vector<std::string> keys(path.begin() + 1, path.end());

    int matched = 0;
    std::vector<std::string> known;
    for (const char* list : {"bodies", "markers", "elements"}) {
      const YAML::Node seq = root[list];
      if (!seq || !seq.IsSequence()) continue;
      for (YAML::Node entry : seq) {
        if (!entry.IsMap() || !entry["name"] || !entry["name"].IsScalar()) continue;
        const std::string name = entry["name"].Scalar();
        known.push_back(name);
        if (glob_match(item, name)) {
          set_path(entry, keys, value);
          ++matched;
        }
      }
    }
    if (matched == 0 && item != "bodies" && item != "markers" && item != "elements") {
      const YAML::Node top = root[item];
      if (top && top.IsMap()) {
        set_path(top, keys, value);
        matched = 1;
      } else if (!top && (item == "time" || item == "integrator" || item == "output" ||
                          item == "operating_point")) {
        root[item] = YAML::Node(YAML::NodeType::Map);
        set_path(root[item], keys, value);
        matched = 1;
      }
    }
    if (matched == 0)
      throw InputError(where + ": no body, marker or element named '" + item + "' (known: " +
                       join(known) + "; or time, integrator, output, operating_point)");
  }
  YAML::Emitter out;
  out << root;
  if (!out.good())
    throw InputError(option + ": cannot write the edited scene: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

SceneSource load_scene_source(const std::string& path, const std::vector<std::string>& params,
                              std::optional<double> t_end) {
  SceneSource src{path, read_scene_text(path), false};
  std::vector<std::string> all = params;
  if (t_end) all.push_back("time.end=" + number_text(*t_end));
  src.text = edit_scene_text(src.text, all);
  src.edited = !all.empty();
  return src;
}

SceneSource edited(const SceneSource& src, const std::vector<std::string>& params,
                   const std::string& option) {
  return SceneSource{src.path, edit_scene_text(src.text, params, option),
                     src.edited || !params.empty()};
}

Scene SceneSource::parse() const {
  if (!edited) return parse_scene(text, path);
  try {
    return parse_scene(text, path);
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) +
                     " (in the scene as changed by --param/--t-end/--sweep; line numbers are "
                     "those of the changed text)");
  }
}

}  // namespace evas::study
