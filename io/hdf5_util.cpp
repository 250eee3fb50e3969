#include "io/hdf5_util.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "io/huge_pages.h"
#include "io/isolated_read.h"

namespace evas::h5 {

namespace {

constexpr hsize_t kCompressMinElements = 256;
constexpr hsize_t kChunkElements = 16384;
hid_t g_open_driver = -1;  // set_open_driver

std::string dset_name(const std::string& name) { return "dataset '" + name + "'"; }
std::string attr_name(const std::string& name) { return "attribute '" + name + "'"; }

Handle string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

bool deflate_available() {
  static const bool avail =
      H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0 && H5Zfilter_avail(H5Z_FILTER_SHUFFLE) > 0;
  return avail;
}

Handle dataset_props(const std::vector<hsize_t>& dims, bool compress) {
  Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (compress && total >= kCompressMinElements && deflate_available()) {
    std::vector<hsize_t> chunk(dims);
    hsize_t inner = 1;
    for (std::size_t i = 1; i < dims.size(); ++i) inner *= dims[i];
    chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(dims[0], kChunkElements / inner));
    H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(plist);
    H5Pset_deflate(plist, 4);
  }
  return plist;
}

void write_raw(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
               hid_t file_type, hid_t mem_type, const void* data, bool compress) {
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  Handle plist = dataset_props(dims, compress);
  Handle dset(H5Dcreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT, plist, H5P_DEFAULT),
              H5Dclose);
  if (!dset.valid()) throw Failure("cannot create " + dset_name(name));
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (total > 0 && H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw Failure("cannot write " + dset_name(name));
}

Handle open_dataset(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) throw Failure(dset_name(name) + " is missing");
  Handle dset(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.valid()) throw Failure(dset_name(name) + " cannot be opened (not a dataset?)");
  return dset;
}

std::vector<hsize_t> dataset_dims(hid_t dset, const std::string& name) {
  Handle space(H5Dget_space(dset), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) throw Failure(dset_name(name) + " has an unreadable shape");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

// The bytes of `obj`'s file, 0 if unknown.
long double file_bytes(hid_t obj) {
  Handle f(H5Iget_file_id(obj), H5Fclose);
  hsize_t size = 0;
  if (!f.valid() || H5Fget_filesize(f, &size) < 0) return 0.0L;
  return static_cast<long double>(size);
}

// True if `bytes` cannot be in obj's file (its size known and smaller).
bool exceeds_file(long double bytes, hid_t obj) {
  const long double file = file_bytes(obj);
  return file > 0.0L && bytes > file;
}

template <class T>
std::vector<T> read_numeric(hid_t loc, const std::string& name, std::vector<hsize_t>& dims,
                            hid_t mem_type, bool integer_only) {
  Handle dset = open_dataset(loc, name);
  Handle type(H5Dget_type(dset), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type);
  if (integer_only ? cls != H5T_INTEGER : (cls != H5T_FLOAT && cls != H5T_INTEGER))
    throw Failure(dset_name(name) + " has the wrong type (expected " +
                  (integer_only ? "integers" : "numbers") + ")");
  dims = dataset_dims(dset, name);
  // A corrupt or hostile file may declare any shape: refuse one whose values
  // could not be held, or that claims far more data than the file stores.
  long double declared = 1.0L;
  for (hsize_t d : dims) declared *= static_cast<long double>(d);
  const long double bytes = declared * static_cast<long double>(sizeof(T));
  const long double stored = stored_bytes(dset);
  if (declared > static_cast<long double>(PTRDIFF_MAX / static_cast<std::ptrdiff_t>(sizeof(T))) ||
      storage_implausible(bytes, stored))
    throw Failure(dset_name(name) + " declares " + std::to_string(static_cast<double>(declared)) +
                  " values but the file stores only " +
                  std::to_string(static_cast<long long>(stored)) + " bytes (corrupt file?)");
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  std::vector<T> out;
  out.reserve(static_cast<std::size_t>(total));
  advise_huge_pages(out.data(), static_cast<std::size_t>(total) * sizeof(T));
  out.resize(static_cast<std::size_t>(total));
  if (total > 0 && H5Dread(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw Failure(dset_name(name) + " cannot be read (file truncated or corrupt?)");
  return out;
}

// Refuses an attribute that holds other than exactly one value (it is read into one).
void expect_single(hid_t attr, const std::string& name) {
  Handle space(H5Aget_space(attr), H5Sclose);
  if (!space.valid() || H5Sget_simple_extent_npoints(space) != 1)
    throw Failure(attr_name(name) + " must hold a single value");
}

Handle open_attribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) <= 0) throw Failure(attr_name(name) + " is missing");
  Handle a(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!a.valid()) throw Failure(attr_name(name) + " cannot be opened");
  return a;
}

herr_t collect_link(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

}  // namespace

bool storage_implausible(long double bytes, long double stored) {
  return bytes > 65536.0L && bytes > 1100.0L * stored;
}

long double stored_bytes(hid_t dset) {
  const long double stored = static_cast<long double>(H5Dget_storage_size(dset));
  const long double file = file_bytes(dset);
  return file > 0.0L && file < stored ? file : stored;
}

Handle& Handle::operator=(Handle&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    close_ = o.close_;
    o.id_ = -1;
  }
  return *this;
}

void Handle::reset() {
  if (id_ >= 0 && close_) close_(id_);
  id_ = -1;
}

Quiet::Quiet() {
  H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Quiet::~Quiet() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }

Handle create_file(const std::string& path) {
  Handle f(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose);
  if (!f.valid()) throw Failure("cannot create the file (directory missing or not writable?)");
  return f;
}

void set_open_driver(hid_t driver) { g_open_driver = driver; }

Handle open_file(const std::string& path, bool writable) {
  const htri_t is = H5Fis_hdf5(path.c_str());
  if (is < 0) throw Failure("cannot open the file (missing or unreadable)");
  if (is == 0) throw Failure("not an HDF5 file");
  Handle fapl;
  if (g_open_driver >= 0 && H5Iis_valid(g_open_driver) > 0) {
    fapl = Handle(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
    if (fapl.valid() && H5Pset_driver(fapl, g_open_driver, nullptr) < 0) fapl.reset();
  }
  Handle f(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY,
                   fapl.valid() ? fapl.get() : H5P_DEFAULT),
           H5Fclose);
  if (!f.valid()) throw Failure("cannot open the HDF5 file (truncated or corrupt?)");
  return f;
}

Handle create_group(hid_t loc, const std::string& name) {
  Handle g(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  if (!g.valid()) throw Failure("cannot create group '" + name + "'");
  return g;
}

Handle open_group(hid_t loc, const std::string& name) {
  if (!exists(loc, name)) throw Failure("group '" + name + "' is missing");
  Handle g(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) throw Failure("'" + name + "' cannot be opened as a group");
  return g;
}

bool exists(hid_t loc, const std::string& path) {
  std::size_t pos = 0;
  while (pos <= path.size()) {
    std::size_t next = path.find('/', pos);
    if (next == std::string::npos) next = path.size();
    if (next > pos) {
      const std::string prefix = path.substr(0, next);
      if (H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    }
    pos = next + 1;
  }
  return true;
}

bool has_attribute(hid_t obj, const std::string& name) { return H5Aexists(obj, name.c_str()) > 0; }

std::vector<std::string> list_links(hid_t group) {
  std::vector<std::string> names;
  H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_link, &names);
  return names;
}

void write_attribute(hid_t obj, const std::string& name, const std::string& value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle type = string_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  const char* p = value.c_str();
  if (!a.valid() || H5Awrite(a, type, &p) < 0) throw Failure("cannot write " + attr_name(name));
}

void write_attribute(hid_t obj, const std::string& name, long long value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!a.valid() || H5Awrite(a, H5T_NATIVE_LLONG, &value) < 0)
    throw Failure("cannot write " + attr_name(name));
}

void write_attribute(hid_t obj, const std::string& name, double value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle a(H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT),
           H5Aclose);
  if (!a.valid() || H5Awrite(a, H5T_NATIVE_DOUBLE, &value) < 0)
    throw Failure("cannot write " + attr_name(name));
}

std::string read_string_attribute(hid_t obj, const std::string& name) {
  Handle a = open_attribute(obj, name);
  Handle ftype(H5Aget_type(a), H5Tclose);
  if (H5Tget_class(ftype) != H5T_STRING) throw Failure(attr_name(name) + " is not a string");
  expect_single(a, name);
  if (H5Tis_variable_str(ftype) > 0) {
    // through the global heap, which libhdf5 trusts: in a child (isolated_read.h)
    return read_isolated(
               [&] {
                 Handle mtype = string_type();
                 char* p = nullptr;
                 if (H5Aread(a, mtype, &p) < 0) throw Failure(attr_name(name) + " cannot be read");
                 std::vector<std::string> s{p ? p : ""};
                 H5free_memory(p);
                 return s;
               },
               attr_name(name))
        .front();
  }
  const std::size_t size = H5Tget_size(ftype);
  // A fixed-size string longer than the file cannot be stored in it (a forged size).
  if (exceeds_file(static_cast<long double>(size), a))
    throw Failure(attr_name(name) + " declares a string of " + std::to_string(size) +
                  " bytes, more than the file holds (corrupt file?)");
  Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mtype, size + 1);
  std::vector<char> buf(size + 1, '\0');
  if (H5Aread(a, mtype, buf.data()) < 0) throw Failure(attr_name(name) + " cannot be read");
  return std::string(buf.data());
}

std::vector<std::optional<std::string>> read_string_attributes(
    hid_t obj, const std::vector<std::string>& names) {
  bool variable = false;
  for (const std::string& n : names) {
    if (!has_attribute(obj, n)) continue;
    Handle a = open_attribute(obj, n);
    Handle t(H5Aget_type(a), H5Tclose);
    variable = variable || (H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) > 0);
  }
  auto read = [&] {  // "" for a missing attribute, "=" + value for one present
    std::vector<std::string> v;
    for (const std::string& n : names)
      v.push_back(has_attribute(obj, n) ? "=" + read_string_attribute(obj, n) : "");
    return v;
  };
  std::string what;
  for (const std::string& n : names) what += (what.empty() ? "" : ", ") + ("'" + n + "'");
  const std::vector<std::string> v = variable ? read_isolated(read, "attribute " + what) : read();
  std::vector<std::optional<std::string>> out(names.size());
  for (std::size_t i = 0; i < names.size() && i < v.size(); ++i)
    if (!v[i].empty()) out[i] = v[i].substr(1);
  return out;
}

long long read_int_attribute(hid_t obj, const std::string& name) {
  Handle a = open_attribute(obj, name);
  Handle ftype(H5Aget_type(a), H5Tclose);
  if (H5Tget_class(ftype) != H5T_INTEGER) throw Failure(attr_name(name) + " is not an integer");
  expect_single(a, name);
  long long v = 0;
  if (H5Aread(a, H5T_NATIVE_LLONG, &v) < 0) throw Failure(attr_name(name) + " cannot be read");
  return v;
}

double read_double_attribute(hid_t obj, const std::string& name) {
  Handle a = open_attribute(obj, name);
  Handle ftype(H5Aget_type(a), H5Tclose);
  const H5T_class_t cls = H5Tget_class(ftype);
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) throw Failure(attr_name(name) + " is not a number");
  expect_single(a, name);
  double v = 0;
  if (H5Aread(a, H5T_NATIVE_DOUBLE, &v) < 0) throw Failure(attr_name(name) + " cannot be read");
  return v;
}

void write_doubles(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                   const double* data, bool compress) {
  write_raw(loc, name, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, compress);
}

void write_int64s(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                  const long long* data, bool compress) {
  write_raw(loc, name, dims, H5T_STD_I64LE, H5T_NATIVE_LLONG, data, compress);
}

void write_int32s(hid_t loc, const std::string& name, const std::vector<hsize_t>& dims,
                  const int* data, bool compress) {
  write_raw(loc, name, dims, H5T_STD_I32LE, H5T_NATIVE_INT, data, compress);
}

void write_strings(hid_t loc, const std::string& name, const std::vector<std::string>& values) {
  Handle type = string_type();
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  Handle dset(H5Dcreate2(loc, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose);
  if (!dset.valid()) throw Failure("cannot create " + dset_name(name));
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  if (n > 0 && H5Dwrite(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0)
    throw Failure("cannot write " + dset_name(name));
}

std::vector<double> read_doubles(hid_t loc, const std::string& name, std::vector<hsize_t>& dims) {
  return read_numeric<double>(loc, name, dims, H5T_NATIVE_DOUBLE, false);
}

std::vector<long long> read_int64s(hid_t loc, const std::string& name, std::vector<hsize_t>& dims) {
  return read_numeric<long long>(loc, name, dims, H5T_NATIVE_LLONG, true);
}

std::vector<std::string> read_strings(hid_t loc, const std::string& name) {
  Handle dset = open_dataset(loc, name);
  Handle ftype(H5Dget_type(dset), H5Tclose);
  if (H5Tget_class(ftype) != H5T_STRING) throw Failure(dset_name(name) + " is not a string list");
  const std::vector<hsize_t> dims = dataset_dims(dset, name);
  if (dims.size() != 1) throw Failure(dset_name(name) + " must be one-dimensional");
  const std::size_t n = dims[0];
  std::vector<std::string> out;
  if (n == 0) return out;
  if (H5Tis_variable_str(ftype) > 0) {
    // through the global heap, which libhdf5 trusts: in a child (isolated_read.h)
    if (exceeds_file(static_cast<long double>(n) * sizeof(char*), dset))
      throw Failure(dset_name(name) + " declares " + std::to_string(n) +
                    " strings, more than the file holds (corrupt file?)");
    return read_isolated(
        [&] {
          Handle mtype = string_type();
          std::vector<char*> ptrs(n, nullptr);
          if (H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0)
            throw Failure(dset_name(name) + " cannot be read");
          std::vector<std::string> v;
          for (char* p : ptrs) {
            v.emplace_back(p ? p : "");
            H5free_memory(p);
          }
          return v;
        },
        dset_name(name));
  }
  const std::size_t size = H5Tget_size(ftype);
  if (exceeds_file(static_cast<long double>(n) * size, dset))
    throw Failure(dset_name(name) + " declares " + std::to_string(n) + " strings of " +
                  std::to_string(size) + " bytes, more than the file holds (corrupt file?)");
  Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(mtype, size);
  std::vector<char> buf(n * size, '\0');
  if (H5Dread(dset, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0)
    throw Failure(dset_name(name) + " cannot be read");
  for (std::size_t i = 0; i < n; ++i) {
    const char* p = buf.data() + i * size;
    out.emplace_back(p, strnlen(p, size));
  }
  return out;
}

Handle create_extendible(hid_t loc, const std::string& name, int rank, hsize_t cols,
                         hsize_t chunk_rows, bool compress) {
  hsize_t dims[2] = {0, cols};
  hsize_t maxdims[2] = {H5S_UNLIMITED, cols};
  hsize_t chunk[2] = {std::max<hsize_t>(1, chunk_rows), std::max<hsize_t>(1, cols)};
  Handle space(H5Screate_simple(rank, dims, maxdims), H5Sclose);
  Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_chunk(plist, rank, chunk);
  if (compress && deflate_available()) {
    H5Pset_shuffle(plist);
    H5Pset_deflate(plist, 4);
  }
  Handle dset(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, plist, H5P_DEFAULT),
              H5Dclose);
  if (!dset.valid()) throw Failure("cannot create " + dset_name(name));
  return dset;
}

void append_rows(hid_t dset, hsize_t cols, hsize_t rows, const double* data) {
  if (rows == 0) return;
  hsize_t cur[2] = {0, 0};
  {
    Handle space(H5Dget_space(dset), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space);
    if (rank < 1 || rank > 2)
      throw Failure("cannot append to a dataset of rank " + std::to_string(rank));
    H5Sget_simple_extent_dims(space, cur, nullptr);
  }
  write_rows(dset, cols, cur[0], rows, data);
}

void write_rows(hid_t dset, hsize_t cols, hsize_t first, hsize_t rows, const double* data) {
  if (rows == 0) return;
  int rank = 0;
  {
    Handle space(H5Dget_space(dset), H5Sclose);
    rank = H5Sget_simple_extent_ndims(space);
    if (rank < 1 || rank > 2)
      throw Failure("cannot write rows to a dataset of rank " + std::to_string(rank));
  }
  hsize_t newdims[2] = {first + rows, cols};
  if (H5Dset_extent(dset, newdims) < 0) throw Failure("cannot extend a dataset");
  Handle fspace(H5Dget_space(dset), H5Sclose);
  hsize_t start[2] = {first, 0};
  hsize_t count[2] = {rows, cols};
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
  Handle mspace(H5Screate_simple(rank, count, nullptr), H5Sclose);
  if (H5Dwrite(dset, H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, data) < 0)
    throw Failure("cannot write rows to a dataset");
}

}  // namespace evas::h5
