// What identifies a file's content without reading it (file_state.h).
#include "model/file_state.h"

#include <sys/stat.h>

namespace evas {

bool file_state(const std::string& path, FileState& out) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  out = {path, static_cast<long long>(st.st_size),
         static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec,
         static_cast<long long>(st.st_ino)};
  return true;
}

bool file_unchanged(const FileState& f) {
  FileState now;
  return file_state(f.path, now) && now == f;
}

}  // namespace evas
