// Scene files (see scene.h): the document (its keys, the time span), the YAML
// syntax checks before it is read, and read_scene / parse_scene. The parts are
// read in scene_bodies.cpp, scene_markers.cpp, scene_elements.cpp and
// scene_output.cpp (the reader is in scene_reader.h).
#include "io/scene.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/scene_reader.h"
#include "solver/system.h"

namespace evas {

namespace scene_detail {

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
              "integrator", "time", "output", "operating_point"});
  scene.name = root["name"] ? text(root["name"], item, "name")
                            : std::filesystem::path(file_).stem().string();
  scene.model = std::make_unique<Model>();
  Model& model = *scene.model;
  if (root["description"]) text(root["description"], item, "description");
  model.gravity = vec3_or(root, "gravity", item, Vec3::Zero());

  // The load is read before the elements: each element that reads it (a
  // piston's pressure map with loads) takes it as it is made.
  if (const Node op = root["operating_point"]) {
    check_keys(op, "operating_point", {"load"});
    if (const Node load = op["load"]) {
      load_ = number(load, "operating_point", "load");
      load_node_.reset(load);
    }
  }

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
  if (load_ && !load_read_)
    fail(load_node_, "operating_point",
         "'load' is given, but no element reads a load (no prescribed piston has a pressure_map "
         "with a load column), so it would be ignored: remove it, or give the maps a load "
         "column");
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
  scene.warnings = std::move(warnings_);
  return scene;
}

}  // namespace scene_detail

namespace {

using scene_detail::kMaxSceneBytes;
using scene_detail::Node;
using scene_detail::SceneReader;

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

std::string read_scene_text(const std::string& path) {
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
  return ss.str();
}

Scene read_scene(const std::string& path) { return parse_scene(read_scene_text(path), path); }

}  // namespace evas
