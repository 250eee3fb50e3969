// Modal-body files read once per process (body_cache.h).
#include "io/body_cache.h"

#include <sys/stat.h>

#include <algorithm>
#include <deque>
#include <mutex>

#include "io/body_file.h"

namespace evas {

namespace {

// What identifies a file's content without reading it.
struct FileState {
  std::string path;
  long long size = -1, mtime_ns = -1, inode = -1;
  bool operator==(const FileState& o) const {
    return path == o.path && size == o.size && mtime_ns == o.mtime_ns && inode == o.inode;
  }
};

bool file_state(const std::string& path, FileState& out) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  out = {path, static_cast<long long>(st.st_size),
         static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec,
         static_cast<long long>(st.st_ino)};
  return true;
}

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

constexpr std::size_t kFiles = 8;      // file bodies kept (the oldest go first)
constexpr std::size_t kDerived = 16;   // derived bodies kept
constexpr std::size_t kMarkers = 512;  // set-marker fits kept

std::mutex lock;
std::deque<FileEntry> files;
std::deque<DerivedEntry> derived;
std::deque<MarkerEntry> markers;

}  // namespace

ModalBody read_body_file_cached(const std::string& path) {
  FileState f;
  if (!file_state(path, f)) return read_body_file(path);  // its own error message
  {
    std::lock_guard<std::mutex> g(lock);
    for (const FileEntry& e : files)
      if (e.file == f) return e.body;
  }
  FileEntry e{f, read_body_file(path)};
  ModalBody out = e.body;
  std::lock_guard<std::mutex> g(lock);
  files.push_back(std::move(e));
  if (files.size() > kFiles) files.pop_front();
  return out;
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
  std::lock_guard<std::mutex> g(lock);
  derived.push_back({f, recipe, body});
  if (derived.size() > kDerived) {
    // its marker fits go with it: they would keep the body alive
    const ModalBody* gone = derived.front().body.get();
    markers.erase(std::remove_if(markers.begin(), markers.end(),
                                 [&](const MarkerEntry& m) { return m.body.get() == gone; }),
                  markers.end());
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

}  // namespace evas
