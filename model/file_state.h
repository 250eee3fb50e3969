// What identifies a file's content without reading it: its path, size, inode
// and modification time. The per-process caches of files that a study or
// sweep reads once per parse (io/body_cache.h, elements/gas_pressure.h) serve
// a file again only while its state is unchanged.
#pragma once

#include <string>

namespace evas {

struct FileState {
  std::string path;
  long long size = -1, mtime_ns = -1, inode = -1;
  bool operator==(const FileState& o) const {
    return path == o.path && size == o.size && mtime_ns == o.mtime_ns && inode == o.inode;
  }
};

/// The state of the regular file `path`; false when it is missing or not a
/// regular file.
bool file_state(const std::string& path, FileState& out);
/// True when the file still has the state `f` (a cache checks this after
/// reading, so that a file replaced during the read is not kept under the
/// state it had before).
bool file_unchanged(const FileState& f);

}  // namespace evas
