// Modal-body files read once per process (body_cache.h).
#include "io/body_cache.h"

#include <algorithm>
#include <deque>
#include <mutex>

#include "io/body_file.h"
#include "model/file_state.h"

namespace evas {

namespace {

struct FileEntry {
  FileState file;
  ModalBody body;
};

struct DerivedEntry {
  FileState file;
  std::string recipe;
  std::shared_ptr<const ModalBody> body;
};

struct MarkerEntry {
  std::shared_ptr<const ModalBody> body;  // held: its address cannot be reused
  std::vector<long> ids;
  std::vector<double> weights;
  bool has_centre = false;
  Vec3 centre = Vec3::Zero();
  Marker marker;
};

struct SurfaceEntry {
  std::shared_ptr<const ModalBody> body;  // held: its address cannot be reused
  SurfaceSet set;
  double rho_c = 0.0;
  bool per_node = false;
  SurfaceRadiation radiation;
};

bool same_set(const SurfaceSet& a, const SurfaceSet& b) {
  return a.nodes == b.nodes && a.area.size() == b.area.size() && a.area == b.area &&
         a.normal.rows() == b.normal.rows() && a.normal == b.normal;
}

constexpr std::size_t kFiles = 8;      // file bodies kept (the oldest go first)
constexpr std::size_t kDerived = 16;   // derived bodies kept
constexpr std::size_t kMarkers = 512;  // set-marker fits kept
constexpr std::size_t kSurfaces = 32;  // surface outputs kept

std::mutex lock;
std::deque<FileEntry> files;
std::deque<FileState> seen;  // files read once (not kept)
std::deque<DerivedEntry> derived;
std::deque<MarkerEntry> markers;
std::deque<SurfaceEntry> surfaces;

}  // namespace

ModalBody read_body_file_cached(const std::string& path) {
  FileState f;
  if (!file_state(path, f)) return read_body_file(path);  // its own error message
  {
    std::lock_guard<std::mutex> g(lock);
    for (const FileEntry& e : files)
      if (e.file == f) return e.body;
  }
  // The first read of a file is not kept: its one use (the scene's body,
  // derived once and kept by derived_body_cached) then costs no copy of the
  // file's 10 MB. A file read a second time (another recipe of it) is kept.
  bool seen_before = false;
  {
    std::lock_guard<std::mutex> g(lock);
    seen_before = std::find(seen.begin(), seen.end(), f) != seen.end();
  }
  ModalBody body = read_body_file(path);
  if (!file_unchanged(f)) return body;  // replaced while read: not kept
  std::lock_guard<std::mutex> g(lock);
  if (!seen_before) {
    seen.push_back(f);
    if (seen.size() > kFiles) seen.pop_front();
    return body;
  }
  files.push_back({f, body});
  if (files.size() > kFiles) files.pop_front();
  return body;
}

std::shared_ptr<const ModalBody> derived_body_cached(
    const std::string& path, const std::string& recipe,
    const std::function<ModalBody(ModalBody)>& derive) {
  FileState f;
  if (!file_state(path, f))
    return std::make_shared<const ModalBody>(derive(read_body_file_cached(path)));
  {
    std::lock_guard<std::mutex> g(lock);
    for (const DerivedEntry& e : derived)
      if (e.file == f && e.recipe == recipe) return e.body;
  }
  auto body = std::make_shared<const ModalBody>(derive(read_body_file_cached(path)));
  if (!file_unchanged(f)) return body;  // replaced while read: not kept
  std::lock_guard<std::mutex> g(lock);
  derived.push_back({f, recipe, body});
  if (derived.size() > kDerived) {
    // its marker fits and surfaces go with it: they would keep the body alive
    const ModalBody* gone = derived.front().body.get();
    markers.erase(std::remove_if(markers.begin(), markers.end(),
                                 [&](const MarkerEntry& m) { return m.body.get() == gone; }),
                  markers.end());
    surfaces.erase(std::remove_if(surfaces.begin(), surfaces.end(),
                                  [&](const SurfaceEntry& m) { return m.body.get() == gone; }),
                   surfaces.end());
    derived.pop_front();
  }
  return body;
}

Marker set_marker_cached(const std::string& name, int body,
                         const std::shared_ptr<const ModalBody>& data,
                         const std::vector<long>& node_ids, const std::vector<double>& weights,
                         const Vec3* centre) {
  auto same = [&](const MarkerEntry& e) {
    return e.body == data && e.ids == node_ids && e.weights == weights &&
           e.has_centre == (centre != nullptr) && (!centre || e.centre == *centre);
  };
  bool cached_body = false;
  {
    std::lock_guard<std::mutex> g(lock);
    for (const MarkerEntry& e : markers)
      if (same(e)) {
        Marker m = e.marker;
        m.name = name;
        m.body = body;
        return m;
      }
    for (const DerivedEntry& e : derived) cached_body = cached_body || e.body == data;
  }
  Marker m = make_set_marker(name, body, *data, node_ids, weights, centre);
  if (!cached_body) return m;
  std::lock_guard<std::mutex> g(lock);
  markers.push_back(
      {data, node_ids, weights, centre != nullptr, centre ? *centre : Vec3::Zero(), m});
  if (markers.size() > kMarkers) markers.pop_front();
  return m;
}

SurfaceRadiation surface_radiation_cached(const std::shared_ptr<const ModalBody>& data,
                                          const SurfaceSet& set, double rho_c, bool per_node,
                                          const std::string& who) {
  auto same = [&](const SurfaceEntry& e) {
    return e.body == data && e.rho_c == rho_c && e.per_node == per_node && same_set(e.set, set);
  };
  bool cached_body = false;
  {
    std::lock_guard<std::mutex> g(lock);
    for (const SurfaceEntry& e : surfaces)
      if (same(e)) return e.radiation;
    for (const DerivedEntry& e : derived) cached_body = cached_body || e.body == data;
  }
  SurfaceRadiation r(*data, set, rho_c, per_node, who);
  if (!cached_body) return r;
  std::lock_guard<std::mutex> g(lock);
  surfaces.push_back({data, set, rho_c, per_node, r});
  if (surfaces.size() > kSurfaces) surfaces.pop_front();
  return r;
}

}  // namespace evas
