// FE pipeline (see fe_pipeline.h and docs/fe-pipeline.md).
#include "io/fe_pipeline.h"

#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include "bodies/interface_modes.h"
#include "io/text_escape.h"

namespace evas {

namespace fs = std::filesystem;

namespace {

std::string tail_of(const std::string& path, int lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  std::string l;
  while (std::getline(in, l)) all.push_back(l);
  std::string out;
  for (std::size_t i = all.size() > static_cast<std::size_t>(lines) ? all.size() - lines : 0;
       i < all.size(); ++i)
    out += "    " + all[i] + "\n";
  return out;
}

/// YAML reading with file:line messages.
struct Yaml {
  std::string file;
  [[noreturn]] void fail(const YAML::Node& n, const std::string& what) const {
    std::ostringstream os;
    os << file;
    if (n.Mark().line >= 0) os << ":" << n.Mark().line + 1;
    os << ": " << what;
    throw InputError(os.str());
  }
  double number(const YAML::Node& n, const std::string& key) const {
    double x = 0.0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, x) || !std::isfinite(x))
      fail(n, "'" + key + "' must be a finite number");
    return x;
  }
  bool boolean(const YAML::Node& n, const std::string& key) const {
    bool b = false;
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, b))
      fail(n, "'" + key + "' must be true or false");
    return b;
  }
  std::string text(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar() || n.Scalar().empty()) fail(n, "'" + key + "' must be a text value");
    return n.Scalar();
  }
  void keys(const YAML::Node& map, const std::string& item,
            const std::set<std::string>& known) const {
    if (!map.IsMap()) fail(map, "'" + item + "' must be a mapping");
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string k = it->first.as<std::string>();
      if (!known.count(k)) {
        std::string list;
        for (const std::string& s : known) list += (list.empty() ? "" : ", ") + s;
        fail(it->first, "unknown key '" + k + "' in " + item + " (known: " + list + ")");
      }
    }
  }
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// An integer >= lo.
int count(const Yaml& y, const YAML::Node& n, const std::string& key, int lo) {
  const double v = y.number(n, key);
  if (v < lo || v != std::floor(v) || v > 1e6)
    y.fail(n, "'" + key + "' must be an integer >= " + std::to_string(lo));
  return static_cast<int>(v);
}

/// `interface_sets: [NAME | {set: NAME, loads: [x, y, z, moments]}]`.
void read_interface_sets(const Yaml& y, const YAML::Node& list, PipelineParams& p) {
  if (!list.IsSequence())
    y.fail(list, "'interface_sets' must be a list of node-set names or {set, loads} maps");
  bool masked = false;
  std::vector<InterfaceLoadMask> masks;
  for (const auto& e : list) {
    InterfaceLoadMask mask;
    if (e.IsMap()) {
      y.keys(e, "an interface_sets entry", {"set", "loads"});
      if (!e["set"]) y.fail(e, "an interface_sets entry needs 'set' (a node-set name)");
      p.interface_sets.push_back(y.text(e["set"], "set"));
      if (e["loads"]) {
        if (!e["loads"].IsSequence() || e["loads"].size() == 0)
          y.fail(e["loads"], "'loads' must be a list of x, y, z, moments");
        mask = InterfaceLoadMask{{false, false, false}, false};
        for (const auto& l : e["loads"]) {
          const std::string w = y.text(l, "loads");
          if (w == "x" || w == "y" || w == "z")
            mask.force[w[0] - 'x'] = true;
          else if (w == "moments")
            mask.moments = true;
          else
            y.fail(l, "unknown load '" + w + "' for set '" + p.interface_sets.back() +
                          "' (known: x, y, z, moments)");
        }
        masked = true;
      }
    } else {
      p.interface_sets.push_back(y.text(e, "interface_sets"));
    }
    masks.push_back(mask);
  }
  if (masked) p.interface.loads = masks;
}

}  // namespace

PipelineParams read_pipeline_params(const std::string& yaml_path, const std::string& out_dir) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::BadFile&) {
    throw InputError(yaml_path + ": cannot open the file");
  } catch (const YAML::Exception& e) {
    throw InputError(yaml_path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  const Yaml y{yaml_path};
  y.keys(root, "the parameter file",
         {"name", "geometry", "parameters", "mesh_size", "units", "material", "modes", "ccx_eigen",
          "ccx_modes", "work_dir", "output", "store_invariants", "reduce"});
  const fs::path base = fs::absolute(fs::path(yaml_path)).parent_path();
  auto resolve = [&](const std::string& p) {
    const fs::path q(p);
    return (q.is_absolute() ? q : base / q).lexically_normal().string();
  };
  PipelineParams p;
  if (root["name"]) p.name = y.text(root["name"], "name");
  if (!root["geometry"]) y.fail(root, "missing key 'geometry' (the Gmsh .geo script)");
  p.geometry = resolve(y.text(root["geometry"], "geometry"));
  if (root["parameters"]) {
    const YAML::Node ps = root["parameters"];
    if (!ps.IsMap()) y.fail(ps, "'parameters' must map script parameter names to numbers");
    for (auto it = ps.begin(); it != ps.end(); ++it)
      p.params[it->first.as<std::string>()] = y.number(it->second, it->first.as<std::string>());
  }
  if (root["mesh_size"]) {
    p.mesh_size = y.number(root["mesh_size"], "mesh_size");
    if (!(p.mesh_size > 0.0)) y.fail(root["mesh_size"], "'mesh_size' must be > 0");
  }
  if (root["units"]) {
    p.units = y.text(root["units"], "units");
    try {
      unit_system(p.units);
    } catch (const InputError& e) {
      y.fail(root["units"], e.what());
    }
  }
  if (root["material"]) {
    const YAML::Node m = root["material"];
    y.keys(m, "material", {"youngs", "poisson", "density"});
    if (m["youngs"]) p.youngs = y.number(m["youngs"], "youngs");
    if (m["poisson"]) p.poisson = y.number(m["poisson"], "poisson");
    if (m["density"]) p.density = y.number(m["density"], "density");
    if (!(p.youngs > 0.0) || !(p.density > 0.0) || !(p.poisson > -1.0 && p.poisson < 0.5))
      y.fail(m, "material needs youngs > 0, density > 0 and -1 < poisson < 0.5");
  }
  if (root["modes"]) {
    const YAML::Node m = root["modes"];
    y.keys(m, "modes",
           {"elastic", "max_frequency", "damping_ratio", "keep_rigid", "solver", "interface_sets",
            "interface_tolerance", "interface_count", "ritz_blocks"});
    if (m["interface_sets"]) read_interface_sets(y, m["interface_sets"], p);
    if (m["interface_tolerance"]) {
      const double t = y.number(m["interface_tolerance"], "interface_tolerance");
      if (!(t > 0.0 && t < 1.0))
        y.fail(m["interface_tolerance"], "'interface_tolerance' must be in (0, 1)");
      p.interface.rank_tolerance = t;
    }
    if (m["interface_count"])
      p.interface.max_count = count(y, m["interface_count"], "interface_count", 1);
    if (m["ritz_blocks"]) p.interface.krylov_blocks = count(y, m["ritz_blocks"], "ritz_blocks", 0);
    if ((m["interface_tolerance"] || m["interface_count"] || m["ritz_blocks"]) &&
        p.interface_sets.empty())
      y.fail(m, "'interface_tolerance', 'interface_count' and 'ritz_blocks' need 'interface_sets'");
    if (m["elastic"]) {
      const double e = y.number(m["elastic"], "elastic");
      if (e < 0 || e != std::floor(e)) y.fail(m["elastic"], "'elastic' must be an integer >= 0");
      p.build.num_elastic = static_cast<int>(e);
    }
    if (m["max_frequency"]) p.build.max_frequency = y.number(m["max_frequency"], "max_frequency");
    if (m["damping_ratio"]) p.build.damping_ratio = y.number(m["damping_ratio"], "damping_ratio");
    if (m["keep_rigid"]) p.build.keep_rigid = m["keep_rigid"].as<bool>();
    if (m["solver"]) p.build.solver = y.text(m["solver"], "solver");
    if (p.build.max_frequency < 0.0 || p.build.damping_ratio < 0.0)
      y.fail(m, "'max_frequency' and 'damping_ratio' must be >= 0");
  } else {
    p.build.num_elastic = 10;
  }
  if (root["store_invariants"])
    p.store_invariants = y.boolean(root["store_invariants"], "store_invariants");
  if (const YAML::Node r = root["reduce"]) {
    y.keys(r, "reduce", {"keep_sets", "extra_nodes"});
    ReduceOptions ro;
    if (const YAML::Node k = r["keep_sets"]) {
      if (k.IsScalar() && k.Scalar() == "all") {
        ro.all_sets = true;
      } else if (k.IsSequence()) {
        ro.all_sets = false;
        for (const auto& n : k) ro.keep_sets.push_back(y.text(n, "keep_sets"));
      } else {
        y.fail(k, "'keep_sets' must be 'all' or a list of node-set names");
      }
    }
    if (const YAML::Node e = r["extra_nodes"]) {
      if (!e.IsSequence()) y.fail(e, "'extra_nodes' must be a list of node ids");
      for (const auto& n : e) {
        const double id = y.number(n, "extra_nodes");
        if (id != std::floor(id)) y.fail(n, "'extra_nodes' must be integer node ids");
        ro.extra_nodes.push_back(static_cast<long>(id));
      }
    }
    p.reduce = ro;
  }
  if (root["ccx_eigen"]) p.ccx_eigen = root["ccx_eigen"].as<bool>();
  if (root["ccx_modes"]) p.ccx_modes = static_cast<int>(y.number(root["ccx_modes"], "ccx_modes"));
  const std::string stem = fs::path(yaml_path).stem().string();
  const fs::path out_base = fs::absolute(out_dir.empty() ? fs::path(".") : fs::path(out_dir));
  auto in_out = [&](const std::string& q) {
    const fs::path r(q);
    return (r.is_absolute() ? r : out_base / r).lexically_normal().string();
  };
  p.work_dir = in_out(root["work_dir"] ? y.text(root["work_dir"], "work_dir") : stem + "-fe");
  p.output = in_out(root["output"] ? y.text(root["output"], "output") : stem + ".h5");
  return p;
}

std::string find_program(const std::vector<std::string>& names) {
  // as the shell searches: PATH unset is /usr/bin:/bin, an empty entry is the
  // current folder
  const char* path = std::getenv("PATH");
  const std::string dirs = path ? path : "/usr/bin:/bin";
  for (const std::string& n : names) {
    std::size_t start = 0;
    while (start <= dirs.size()) {
      const std::size_t end = std::min(dirs.find(':', start), dirs.size());
      const fs::path f = fs::path(end > start ? dirs.substr(start, end - start) : ".") / n;
      std::error_code ec;
      if (fs::is_regular_file(f, ec) && access(f.c_str(), X_OK) == 0) return f.string();
      start = end + 1;
    }
  }
  return "";
}

void run_logged(const std::string& what, const std::string& command, const std::string& log) {
  const std::string full = command + " > " + shell_quote(log) + " 2>&1";
  const int rc = std::system(full.c_str());
  const int status = (rc != -1 && WIFEXITED(rc)) ? WEXITSTATUS(rc) : -1;
  if (status != 0) {
    std::ostringstream os;
    os << what << " failed (exit status " << status << "); command: " << command
       << "\n  log: " << log << "\n  last lines:\n"
       << tail_of(log, 8);
    throw InputError(os.str());
  }
}

void run_gmsh(const std::string& geo, const std::map<std::string, double>& params, double mesh_size,
              const std::string& out_inp, const std::string& log) {
  const std::string gmsh = find_program({"gmsh"});
  if (gmsh.empty())
    throw InputError("gmsh is not installed or not on PATH (Debian: apt-get install gmsh)");
  if (!fs::exists(geo)) throw InputError(geo + ": geometry script not found");
  std::ostringstream cmd;
  cmd.precision(17);
  cmd << shell_quote(gmsh) << " -3 -nopopup " << shell_quote(geo);
  for (const auto& [k, v] : params) cmd << " -setnumber " << shell_quote(k) << " " << v;
  if (mesh_size > 0.0) cmd << " -setnumber mesh_size " << mesh_size;
  cmd << " -format inp -o " << shell_quote(out_inp);
  run_logged("gmsh", cmd.str(), log);
  if (!fs::exists(out_inp))
    throw InputError("gmsh wrote no mesh " + out_inp + " (log: " + log + ")");
}

void write_ccx_deck(const std::string& dir, const std::string& job, const std::string& mesh_file,
                    double youngs, double poisson, double density, bool matrix_storage, int modes) {
  const std::string path = (fs::path(dir) / (job + ".inp")).string();
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot write the file");
  out.precision(12);  // ccx reads at most 20 characters per field
  out << "** evas FE pipeline: " << (matrix_storage ? "matrix storage" : "eigenmodes") << "\n"
      << "*INCLUDE, INPUT=" << mesh_file << "\n"
      << "*MATERIAL, NAME=MAT\n*ELASTIC\n"
      << youngs << ", " << poisson << "\n*DENSITY\n"
      << density << "\n*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n*STEP\n";
  if (matrix_storage)
    out << "*FREQUENCY, SOLVER=MATRIXSTORAGE\n10\n";
  else
    out << "*FREQUENCY\n" << modes << "\n*NODE FILE\nU\n";
  out << "*END STEP\n";
  if (!out) throw InputError(path + ": write failed");
}

void run_ccx(const std::string& dir, const std::string& job,
             const std::vector<std::string>& expect) {
  const std::string ccx = find_program({"ccx", "ccx_2.20", "ccx_2.21", "ccx_2.19"});
  if (ccx.empty())
    throw InputError(
        "CalculiX ccx is not installed or not on PATH (Debian: apt-get install "
        "calculix-ccx)");
  const std::string log = (fs::path(dir) / (job + ".log")).string();
  for (const std::string& e : expect) fs::remove(fs::path(dir) / (job + e));
  run_logged("ccx",
             "cd " + shell_quote(dir) + " && OMP_NUM_THREADS=${OMP_NUM_THREADS:-2} " +
                 shell_quote(ccx) + " -i " + shell_quote(job),
             log);
  for (const std::string& e : expect) {
    const fs::path f = fs::path(dir) / (job + e);
    if (!fs::exists(f) || fs::file_size(f) == 0)
      throw InputError("ccx wrote no " + f.string() + " (log: " + log + ")\n  last lines:\n" +
                       tail_of(log, 8));
  }
  // ccx prints "*ERROR" and may still exit 0.
  std::ifstream in(log);
  std::string l;
  while (std::getline(in, l))
    if (l.find("*ERROR") != std::string::npos)
      throw InputError("ccx reported an error (log: " + log + "): " + l);
}

PipelineResult run_pipeline(const PipelineParams& p, bool verbose) {
  PipelineResult res;
  const UnitSystem units = unit_system(p.units);
  std::error_code ec;
  fs::create_directories(p.work_dir, ec);
  if (ec) throw InputError(p.work_dir + ": cannot create the work folder: " + ec.message());
  const std::string dir = p.work_dir;
  auto stage = [&](const std::string& name, auto&& fn) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    res.stages.push_back({name, seconds_since(t0)});
    if (verbose) std::printf("  %-28s %8.2f s\n", name.c_str(), res.stages.back().seconds);
    std::fflush(stdout);
  };
  const std::string gmsh_inp = (fs::path(dir) / "gmsh.inp").string();
  stage("gmsh mesh", [&] {
    run_gmsh(p.geometry, p.params, p.mesh_size, gmsh_inp, (fs::path(dir) / "gmsh.log").string());
  });
  InpMesh mesh;
  std::map<std::string, SurfaceSet> surfaces;
  stage("read mesh, write decks", [&] {
    mesh = read_inp(gmsh_inp);
    surfaces = mesh_surfaces(mesh, units, gmsh_inp);
    write_ccx_mesh((fs::path(dir) / "mesh.inp").string(), mesh);
    write_ccx_deck(dir, "matrices", "mesh.inp", p.youngs, p.poisson, p.density, true, 0);
  });
  stage("ccx matrix storage", [&] { run_ccx(dir, "matrices", {".sti", ".mas", ".dof"}); });
  stage("read matrices", [&] {
    const InpMesh solid = read_inp((fs::path(dir) / "mesh.inp").string());
    const auto f = [&](const char* ext) {
      return (fs::path(dir) / ("matrices" + std::string(ext))).string();
    };
    res.fe = read_matrix_storage(solid, f(".sti"), f(".mas"), f(".dof"), units);
  });
  if (verbose)
    std::printf(
        "  mesh: %d nodes, %d DOF, K %ld non-zeros\n", static_cast<int>(res.fe.node_ids.size()),
        3 * static_cast<int>(res.fe.node_ids.size()), static_cast<long>(res.fe.K.nonZeros()));
  stage("evas eigen-solution", [&] { res.body = build_modal_body(p.name, res.fe, p.build); });
  // the areas and normals of the body's sets that are mesh faces (ERP outputs)
  for (auto& [name, s] : surfaces)
    if (res.body.node_sets.count(name)) res.body.surfaces.emplace(name, std::move(s));
  if (!p.interface_sets.empty())
    stage("interface modes", [&] {
      InterfaceOptions io = p.interface;
      io.damping_ratio = p.build.damping_ratio;
      res.body = add_interface_modes_by_name(res.fe, res.body, p.interface_sets, io);
    });
  if (p.store_invariants || p.reduce)
    stage(p.reduce ? "invariants, reduce body" : "store invariants", [&] {
      store_full_body_data(res.body);
      if (p.reduce) res.body = reduce_body(res.body, *p.reduce);
    });
  if (p.ccx_eigen) {
    const int n = p.ccx_modes > 0 ? p.ccx_modes : std::max(16, 6 + p.build.num_elastic + 4);
    write_ccx_deck(dir, "eigen", "mesh.inp", p.youngs, p.poisson, p.density, false, n);
    stage("ccx eigen-solution", [&] { run_ccx(dir, "eigen", {".frd", ".dat"}); });
    res.frd = (fs::path(dir) / "eigen.frd").string();
    res.dat = (fs::path(dir) / "eigen.dat").string();
  }
  return res;
}

}  // namespace evas
