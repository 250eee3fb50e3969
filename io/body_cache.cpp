// Modal-body files read once per process (body_cache.h).
#include "io/body_cache.h"

#include <sys/stat.h>

#include <deque>
#include <mutex>

#include "io/body_file.h"

namespace evas {

namespace {

struct Entry {
  std::string path;
  long long size = -1, mtime_ns = -1, inode = -1;
  ModalBody body;
};

constexpr std::size_t kEntries = 8;  // bodies kept (the oldest go first)

}  // namespace

ModalBody read_body_file_cached(const std::string& path) {
  static std::mutex lock;
  static std::deque<Entry> cache;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    return read_body_file(path);  // its own error message
  const long long mtime =
      static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
  {
    std::lock_guard<std::mutex> g(lock);
    for (const Entry& e : cache)
      if (e.path == path && e.size == st.st_size && e.mtime_ns == mtime &&
          e.inode == static_cast<long long>(st.st_ino))
        return e.body;
  }
  Entry e{path, st.st_size, mtime, static_cast<long long>(st.st_ino), read_body_file(path)};
  ModalBody out = e.body;
  std::lock_guard<std::mutex> g(lock);
  cache.push_back(std::move(e));
  if (cache.size() > kEntries) cache.pop_front();
  return out;
}

}  // namespace evas
