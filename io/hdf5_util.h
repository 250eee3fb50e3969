// Thin RAII layer over the HDF5 C API, shared by the io/ readers and writers.
//
// Every helper throws h5::Failure with a short message naming the object
// ("dataset '/modes/shapes': ..."); callers add the file name and turn it into
// InputError (reading input) or RunError (writing results). Dataset layout is
// row-major as HDF5 stores it: a dims = {rows, cols} dataset of doubles is
// read into a row-major buffer.
#pragma once

#include <hdf5.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace evas::h5 {

class Failure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Owns one HDF5 identifier and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept;
  ~Handle() { reset(); }

  void reset();
  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

/// Turns off HDF5's automatic error printing while alive (errors become exceptions).
class Quiet {
 public:
  Quiet();
  ~Quiet();
  Quiet(const Quiet&) = delete;
  Quiet& operator=(const Quiet&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

Handle create_file(const std::string& path);
/// Opens an existing file; throws if it is not an HDF5 file or cannot be read.
Handle open_file(const std::string& path, bool writable = false);
/// The file driver open_file uses from now on (a POSIX one; default HDF5's).
/// The results writer sets its own (io/write_guard.h): HDF5 sees a file open
/// twice in one process as one file only when both use the same driver.
void set_open_driver(hid_t driver);
Handle create_group(hid_t loc, const std::string& name);
Handle open_group(hid_t loc, const std::string& name);

/// True if every component of the slash-separated path exists below loc.
bool exists(hid_t loc, const std::string& path);
bool has_attribute(hid_t obj, const std::string& name);
/// Names of the links directly below a group, in name order.
std::vector<std::string> list_links(hid_t group);

void write_attribute(hid_t obj, const std::string& name, const std::string& value);
void write_attribute(hid_t obj, const std::string& name, long long value);
void write_attribute(hid_t obj, const std::string& name, double value);
std::string read_string_attribute(hid_t obj, const std::string& name);
/// The string attributes `names` of obj, empty where one is missing, read in one
/// child process when any is variable-length (isolated_read.h).
std::vector<std::optional<std::string>> read_string_attributes(
    hid_t obj, const std::vector<std::string>& names);
long long read_int_attribute(hid_t obj, const std::string& name);
double read_double_attribute(hid_t obj, const std::string& name);

/// Fixed-size dataset; with `compress`, compressed (chunked, shuffle + deflate 4)
/// when large enough, otherwise contiguous.
void write_doubles(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const double* data, bool compress = true);
void write_int64s(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                  const long long* data, bool compress = true);
void write_int32s(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                  const int* data, bool compress = true);
void write_strings(hid_t loc, const std::string& name, const std::vector<std::string>& values);

/// Bytes stored for a dataset: HDF5's storage size, at most the file's size
/// (a corrupt or forged layout may claim more than the file holds).
long double stored_bytes(hid_t dset);
/// True when a dataset of `bytes` declared cannot come from `stored` bytes of
/// the file: above 64 kB and more than 1100 times what is stored (deflate
/// reaches about 1000:1 on constant data): a truncated or forged file.
bool storage_implausible(long double bytes, long double stored);

/// Reads a whole dataset (converted to the requested type) and its dims.
std::vector<double> read_doubles(hid_t loc, const std::string& name, std::vector<hsize_t>& dims);
std::vector<long long> read_int64s(hid_t loc, const std::string& name, std::vector<hsize_t>& dims);
std::vector<std::string> read_strings(hid_t loc, const std::string& name);

/// Extendible, chunked dataset of doubles: dims {0} (rank 1) or {0, cols}
/// (rank 2, cols >= 1); with `compress`, shuffle + deflate (level 4).
Handle create_extendible(hid_t loc, const std::string& name, int rank, hsize_t cols,
                         hsize_t chunk_rows, bool compress);
/// Appends `rows` rows (row-major; `cols` values each, 1 for a rank-1 dataset).
void append_rows(hid_t dset, hsize_t cols, hsize_t rows, const double* data);
/// Sets the extent to first + rows rows and writes rows [first, first + rows):
/// rows placed by a count the caller keeps, not by the dataset's current extent.
void write_rows(hid_t dset, hsize_t cols, hsize_t first, hsize_t rows, const double* data);

}  // namespace evas::h5
