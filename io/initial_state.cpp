// A model's state as a file (initial_state.h).
#include "io/initial_state.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace evas {

std::string exact_list_text(const double* x, int n) {
  std::ostringstream o;
  o << "[";
  char buf[40];
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "%.17g", x[i]);
    o << (i ? ", " : "") << buf;
  }
  o << "]";
  return o.str();
}

std::string initial_state_text(const Model& model, const Vec& q, const Vec& v,
                               const std::string& scene, double t, const std::string& comment) {
  std::ostringstream o;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) o << "# " << line << "\n";
  YAML::Emitter name;
  name << scene;
  o << "scene: " << name.c_str() << "\n";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", t);
  o << "t: " << buf << "\nbodies:\n";
  for (const Body& b : model.bodies()) {
    YAML::Emitter bn;
    bn << b.name;
    o << "  - {name: " << bn.c_str() << ",\n     q: " << exact_list_text(q.data() + b.offset, b.n())
      << ",\n     v: " << exact_list_text(v.data() + b.offset, b.n()) << "}\n";
  }
  return o.str();
}

void apply_initial_state(Model& model, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot read the state file: " + e.what());
  }
  const YAML::Node bodies = root["bodies"];
  if (!bodies || !bodies.IsSequence())
    throw InputError(path + ": a state file lists 'bodies', each {name, q, v}");
  std::set<std::string> seen;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const YAML::Node b = bodies[k];
    const std::string item = path + ": bodies[" + std::to_string(k) + "]";
    if (!b.IsMap() || !b["name"]) throw InputError(item + ": needs 'name', 'q' and 'v'");
    const std::string name = b["name"].as<std::string>();
    Body* body = nullptr;
    for (Body& c : model.bodies())
      if (c.name == name) body = &c;
    if (!body) throw InputError(item + ": the scene has no body '" + name + "'");
    if (!seen.insert(name).second) throw InputError(item + ": body '" + name + "' again");
    for (const char* key : {"q", "v"}) {
      const YAML::Node x = b[key];
      if (!x || !x.IsSequence() || static_cast<int>(x.size()) != body->n())
        throw InputError(item + " (" + name + "): '" + key + "' must list " +
                         std::to_string(body->n()) + " numbers, one per mode of the body");
      Vec val(body->n());
      for (int i = 0; i < body->n(); ++i) {
        double d = 0.0;
        try {
          d = x[static_cast<std::size_t>(i)].as<double>();
        } catch (const std::exception&) {
          d = std::nan("");
        }
        if (!std::isfinite(d))
          throw InputError(item + " (" + name + "): " + key + "[" + std::to_string(i) +
                           "] is not a finite number");
        val[i] = d;
      }
      (key[0] == 'q' ? body->q0 : body->v0) = val;
    }
  }
  for (const Body& b : model.bodies())
    if (!seen.count(b.name))
      throw InputError(path + ": the state leaves out body '" + b.name +
                       "' (every body of the scene is needed)");
}

}  // namespace evas
