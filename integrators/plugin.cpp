#include "integrators/plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

#include "integrators/integrator.h"

namespace evas {

namespace {

namespace fs = std::filesystem;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

bool is_path(const std::string& spec) {
  return spec.find('/') != std::string::npos ||
         (spec.size() > 3 && spec.compare(spec.size() - 3, 3, ".so") == 0);
}

fs::path find_plugin(const std::string& spec) {
  if (spec.empty()) throw InputError("plug-in: empty name");
  if (is_path(spec)) {
    std::error_code ec;
    if (!fs::is_regular_file(spec, ec)) throw InputError("plug-in '" + spec + "': no such file");
    return fs::absolute(spec);
  }
  const char* env = std::getenv("EVAS_PLUGIN_PATH");
  const std::vector<std::string> dirs = split(env ? env : "", ':');
  for (const std::string& d : dirs)
    for (const std::string& file : {"lib" + spec + ".so", spec + ".so"}) {
      const fs::path p = fs::path(d) / file;
      std::error_code ec;
      if (fs::is_regular_file(p, ec)) return fs::absolute(p);
    }
  throw InputError("plug-in '" + spec + "': not found as lib" + spec + ".so or " + spec +
                   ".so in EVAS_PLUGIN_PATH (" +
                   (dirs.empty() ? std::string("unset") : std::string(env)) +
                   "); give a path to the .so file instead");
}

}  // namespace

std::vector<std::string> load_plugin(const std::string& spec) {
  static std::mutex m;
  static std::map<std::string, std::vector<std::string>> loaded;  // file -> names
  const fs::path file = find_plugin(spec);
  std::lock_guard<std::mutex> lock(m);
  const std::string key = fs::weakly_canonical(file).string();
  if (const auto it = loaded.find(key); it != loaded.end()) return it->second;
  // RTLD_NOW: unresolved symbols fail here, not in the middle of a run
  void* handle = dlopen(key.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw InputError("plug-in '" + key + "': cannot be loaded: " + (why ? why : "?"));
  }
  using Init = int (*)(int);
  dlerror();
  void* sym = dlsym(handle, "evas_plugin_init");
  if (!sym) {
    dlclose(handle);
    throw InputError("plug-in '" + key +
                     "': has no entry point evas_plugin_init (extern \"C\" int "
                     "evas_plugin_init(int abi_version))");
  }
  const std::vector<std::string> before = integrator_names();
  int rc = 0;
  try {
    rc = reinterpret_cast<Init>(sym)(EVAS_PLUGIN_ABI_VERSION);
  } catch (const std::exception& e) {
    // the library stays loaded: integrators it registered before throwing
    // refer to its code
    throw InputError("plug-in '" + key + "': " + e.what());
  }
  if (rc != 0)
    throw InputError("plug-in '" + key + "': evas_plugin_init(" +
                     std::to_string(EVAS_PLUGIN_ABI_VERSION) + ") returned " + std::to_string(rc) +
                     " (built for another plug-in ABI version?)");
  const std::vector<std::string> after = integrator_names();
  std::vector<std::string> added(after.begin() + static_cast<long>(before.size()), after.end());
  if (added.empty()) throw InputError("plug-in '" + key + "': registered no integrator");
  loaded[key] = added;
  return added;  // the handle is kept open for the life of the process
}

std::vector<std::string> load_env_plugins() {
  std::vector<std::string> names;
  const char* env = std::getenv("EVAS_PLUGINS");
  if (!env) return names;
  for (const std::string& spec : split(env, ':')) {
    const std::vector<std::string> n = load_plugin(spec);
    names.insert(names.end(), n.begin(), n.end());
  }
  return names;
}

}  // namespace evas
