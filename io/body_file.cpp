#include "io/body_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>

#include "io/hdf5_util.h"
#include "io/huge_pages.h"
#include "model/invariants.h"

namespace evas {

namespace {

using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? " x " : "") + std::to_string(dims[i]);
  return s + (dims.size() == 1 ? ",)" : ")");
}

void expect_shape(const std::string& name, const std::vector<hsize_t>& dims,
                  const std::vector<hsize_t>& want) {
  if (dims != want)
    throw h5::Failure("dataset '" + name + "' has shape " + shape_text(dims) + ", expected " +
                      shape_text(want));
}

// A value that occurs twice in the sorted `values` (the smallest such), or none.
template <class T>
std::optional<T> repeat_in_sorted(const std::vector<T>& values) {
  const auto rep = std::adjacent_find(values.begin(), values.end());
  if (rep == values.end()) return std::nullopt;
  return *rep;
}

void expect_finite(const std::string& name, const std::vector<double>& v) {
  // a first pass over the exponent bits (all ones: Inf or NaN), which vectorizes;
  // the value is located only when there is one
  constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
  std::uint64_t any = 0;
  for (double x : v) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    any |= static_cast<std::uint64_t>((bits & kExponent) == kExponent);
  }
  if (any == 0) return;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw h5::Failure("dataset '" + name + "' has a non-finite value at flat index " +
                        std::to_string(i));
}

// Body files are written without compression: modal data (doubles) deflate by
// about 15 % only, and inflating them took 5 % of a whole run of the paper's
// engine (both kept bodies, docs/engine-speed.md).
constexpr bool kStoreCompressed = false;

// Limits checked before a dataset is read, so that a corrupt or hostile file
// is refused with a message instead of an allocation failure.
constexpr long double kMaxValues = 2147483647.0L;  // per dataset: Eigen's int indices

std::string bytes_text(long double b) {
  char buf[64];
  if (b >= 1e6L)
    std::snprintf(buf, sizeof buf, "%.3Lg MB", b / 1e6L);
  else
    std::snprintf(buf, sizeof buf, "%.0Lf bytes", b);
  return buf;
}

// Shape of a dataset, refused when it declares more values than the limit or
// more than the file holds for it. Nothing is read.
std::vector<hsize_t> checked_dims(hid_t file, const std::string& name) {
  if (!h5::exists(file, name)) throw h5::Failure("dataset '" + name + "' is missing");
  h5::Handle d(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) throw h5::Failure("dataset '" + name + "' cannot be opened (not a dataset?)");
  h5::Handle space(H5Dget_space(d), H5Sclose);
  const int rank = space.valid() ? H5Sget_simple_extent_ndims(space) : -1;
  if (rank < 0 || rank > 4)
    throw h5::Failure("dataset '" + name + "' has an unreadable shape (rank " +
                      std::to_string(rank) + ")");
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  long double total = 1.0L;
  for (hsize_t x : dims) total *= static_cast<long double>(x);
  if (total > kMaxValues) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.4Lg", total);
    throw h5::Failure("dataset '" + name + "' declares shape " + shape_text(dims) + ", " + buf +
                      " values, more than the limit of 2147483647 values per dataset (corrupt "
                      "file?)");
  }
  h5::Handle type(H5Dget_type(d), H5Tclose);
  const long double bytes = total * (type.valid() ? H5Tget_size(type) : 8);
  const long double stored = h5::stored_bytes(d);
  if (h5::storage_implausible(bytes, stored))
    throw h5::Failure("dataset '" + name + "' declares shape " + shape_text(dims) + " (" +
                      bytes_text(bytes) + ") but the file stores only " + bytes_text(stored) +
                      " for it: the file is truncated or corrupt");
  return dims;
}

// Reads a dataset after checked_dims; with `want`, a shape other than `want`
// is refused before reading.
std::vector<double> read_doubles(hid_t file, const std::string& name, std::vector<hsize_t>& dims,
                                 const std::vector<hsize_t>* want = nullptr) {
  dims = checked_dims(file, name);
  if (want) expect_shape(name, dims, *want);
  return h5::read_doubles(file, name, dims);
}

std::vector<long long> read_int64s(hid_t file, const std::string& name, std::vector<hsize_t>& dims,
                                   const std::vector<hsize_t>* want = nullptr) {
  dims = checked_dims(file, name);
  if (want) expect_shape(name, dims, *want);
  return h5::read_int64s(file, name, dims);
}

// The row-major rows x cols values of a file into the column-major `m`, a
// block of rows at a time: each block is read as stored and written down the
// columns while it is in cache. Element by element, the transpose of the
// block body's 9.4 MB of shapes strided through memory and took most of the
// body's reading (docs/engine-speed.md, "Start-up").
void assign_row_major(Mat& m, const std::vector<double>& v, Eigen::Index rows, Eigen::Index cols) {
  m.resize(rows, cols);
  advise_huge_pages(m.data(), v.size() * sizeof(double));
  constexpr Eigen::Index kBlock = 64;
  for (Eigen::Index r0 = 0; r0 < rows; r0 += kBlock) {
    const Eigen::Index nr = std::min(kBlock, rows - r0);
    m.middleRows(r0, nr) = Eigen::Map<const RowMat>(v.data() + r0 * cols, nr, cols);
  }
}

bool is_diagonal(const SpMat& M) {
  for (int k = 0; k < M.outerSize(); ++k)
    for (SpMat::InnerIterator it(M, k); it; ++it)
      if (it.row() != it.col() && it.value() != 0.0) return false;
  return true;
}

void write_body(hid_t file, const ModalBody& body) {
  const int N = body.num_nodes();
  const int n = body.num_modes();
  const hsize_t uN = static_cast<hsize_t>(N), un = static_cast<hsize_t>(n);
  h5::write_attribute(file, "format", std::string(kBodyFormat));
  h5::write_attribute(file, "version", static_cast<long long>(kBodyFormatVersion));
  h5::write_attribute(file, "name", body.name);
  h5::write_attribute(file, "length_unit", std::string("m"));
  h5::write_attribute(file, "mass_unit", std::string("kg"));
  h5::write_attribute(file, "reduced", static_cast<long long>(body.reduced() ? 1 : 0));
  if (body.reduced())
    h5::write_attribute(file, "full_num_nodes", static_cast<long long>(body.full_num_nodes));

  {
    h5::Handle g = h5::create_group(file, "nodes");
    std::vector<long long> ids(body.node_ids.begin(), body.node_ids.end());
    h5::write_int64s(g, "ids", {uN}, ids.data(), kStoreCompressed);
    RowMat s = body.s;
    h5::write_doubles(g, "coordinates", {uN, 3}, s.data(), kStoreCompressed);
  }
  if (!body.reduced()) {
    h5::Handle g = h5::create_group(file, "mass");
    if (is_diagonal(body.mass)) {
      Vec d = body.mass.diagonal();
      h5::write_doubles(g, "lumped", {uN}, d.data(), kStoreCompressed);
    } else {
      Eigen::SparseMatrix<double, Eigen::RowMajor, int> csr = body.mass;
      csr.makeCompressed();
      h5::Handle c = h5::create_group(g, "consistent");
      std::vector<long long> indptr(csr.outerIndexPtr(), csr.outerIndexPtr() + N + 1);
      std::vector<long long> indices(csr.innerIndexPtr(), csr.innerIndexPtr() + csr.nonZeros());
      h5::write_int64s(c, "indptr", {uN + 1}, indptr.data(), kStoreCompressed);
      h5::write_int64s(c, "indices", {static_cast<hsize_t>(indices.size())}, indices.data(),
                       kStoreCompressed);
      h5::write_doubles(c, "values", {static_cast<hsize_t>(indices.size())}, csr.valuePtr(),
                        kStoreCompressed);
    }
  }
  {
    h5::Handle g = h5::create_group(file, "modes");
    h5::write_doubles(g, "eigenvalues", {un}, body.eigenvalues.data(), kStoreCompressed);
    RowMat shapes = body.modes;
    h5::write_doubles(g, "shapes", {3 * uN, un}, shapes.data(), kStoreCompressed);
    h5::write_doubles(g, "damping", {un}, body.damping.data(), kStoreCompressed);
    std::vector<int> kinds;
    for (ModeKind k : body.kinds) kinds.push_back(static_cast<int>(k));
    h5::write_int32s(g, "kind", {un}, kinds.data(), kStoreCompressed);
  }
  {
    h5::Handle g = h5::create_group(file, "sets");
    for (const auto& [name, ids] : body.node_sets) {
      std::vector<long long> v(ids.begin(), ids.end());
      h5::write_int64s(g, name, {static_cast<hsize_t>(v.size())}, v.data(), kStoreCompressed);
    }
  }
  if (!body.surfaces.empty()) {
    // per surface set: node ids, areas [m^2], outward unit normals (N x 3)
    h5::Handle g = h5::create_group(file, "surfaces");
    for (const auto& [name, sf] : body.surfaces) {
      h5::Handle sg = h5::create_group(g, name);
      const auto ns = static_cast<hsize_t>(sf.nodes.size());
      std::vector<long long> v(sf.nodes.begin(), sf.nodes.end());
      h5::write_int64s(sg, "nodes", {ns}, v.data(), kStoreCompressed);
      h5::write_doubles(sg, "area", {ns}, sf.area.data(), kStoreCompressed);
      RowMat nrm = sf.normal;
      h5::write_doubles(sg, "normal", {ns, 3}, nrm.data(), kStoreCompressed);
    }
  }
  if (body.invariants) {
    const ModalInvariants& inv = *body.invariants;
    h5::Handle g = h5::create_group(file, "invariants");
    RowMat S = inv.S;
    h5::write_doubles(g, "S", {3, un}, S.data(), kStoreCompressed);
    std::vector<double> p, M;
    p.reserve(9 * n);
    M.reserve(9 * static_cast<std::size_t>(n) * n);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        p.insert(p.end(), inv.p[a][b].data(), inv.p[a][b].data() + n);
        const RowMat Mab = inv.M[a][b];
        M.insert(M.end(), Mab.data(), Mab.data() + Mab.size());
      }
    h5::write_doubles(g, "p", {3, 3, un}, p.data(), kStoreCompressed);
    h5::write_doubles(g, "M", {3, 3, un, un}, M.data(), kStoreCompressed);
  }
  if (body.mass_props) {
    const MassProperties& mp = *body.mass_props;
    h5::Handle g = h5::create_group(file, "mass_properties");
    h5::write_doubles(g, "mass", {1}, &mp.mass, kStoreCompressed);
    h5::write_doubles(g, "centre_of_mass", {3}, mp.com.data(), kStoreCompressed);
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> J = mp.inertia, E = mp.principal_axes;
    h5::write_doubles(g, "inertia", {3, 3}, J.data(), kStoreCompressed);
    h5::write_doubles(g, "principal_moments", {3}, mp.principal_moments.data(), kStoreCompressed);
    h5::write_doubles(g, "principal_axes", {3, 3}, E.data(), kStoreCompressed);
  }
}

// /invariants and /mass_properties (version 2, optional).
void read_stored(hid_t file, ModalBody& body) {
  std::vector<hsize_t> dims;
  const hsize_t n = static_cast<hsize_t>(body.num_modes());
  const Eigen::Index in = static_cast<Eigen::Index>(n);
  if (h5::exists(file, "/invariants")) {
    auto inv = std::make_shared<ModalInvariants>();
    const std::vector<hsize_t> wS = {3, n}, wp = {3, 3, n}, wM = {3, 3, n, n};
    const std::vector<double> S = read_doubles(file, "/invariants/S", dims, &wS);
    expect_finite("/invariants/S", S);
    inv->S = Eigen::Map<const RowMat>(S.data(), 3, in);
    const std::vector<double> p = read_doubles(file, "/invariants/p", dims, &wp);
    expect_finite("/invariants/p", p);
    const std::vector<double> M = read_doubles(file, "/invariants/M", dims, &wM);
    expect_finite("/invariants/M", M);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const std::size_t ab = static_cast<std::size_t>(3 * a + b);
        inv->p[a][b] = Eigen::Map<const Vec>(p.data() + ab * n, in);
        inv->M[a][b] = Eigen::Map<const RowMat>(M.data() + ab * n * n, in, in);
      }
    body.invariants = std::move(inv);
  }
  if (h5::exists(file, "/mass_properties")) {
    MassProperties mp;
    auto read = [&](const std::string& name, const std::vector<hsize_t>& shape) {
      const std::string path = "/mass_properties/" + name;
      std::vector<double> v = read_doubles(file, path, dims, &shape);
      expect_finite(path, v);
      return v;
    };
    mp.mass = read("mass", {1})[0];
    if (!(mp.mass > 0.0)) throw h5::Failure("dataset '/mass_properties/mass' must be positive");
    const std::vector<double> c = read("centre_of_mass", {3});
    mp.com = Vec3(c[0], c[1], c[2]);
    using RowMat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
    mp.inertia = Eigen::Map<const RowMat3>(read("inertia", {3, 3}).data());
    const std::vector<double> pm = read("principal_moments", {3});
    mp.principal_moments = Vec3(pm[0], pm[1], pm[2]);
    mp.principal_axes = Eigen::Map<const RowMat3>(read("principal_axes", {3, 3}).data());
    body.mass_props = mp;
  }
}

ModalBody read_body(hid_t file) {
  ModalBody body;
  // the string attributes in one child process (io/isolated_read.h)
  const std::vector<std::optional<std::string>> text =
      h5::read_string_attributes(file, {"format", "name", "length_unit", "mass_unit"});
  if (!text[0]) throw h5::Failure("attribute 'format' is missing (not an evas modal-body file)");
  const std::string& format = *text[0];
  if (format != kBodyFormat)
    throw h5::Failure("attribute 'format' is '" + format + "', expected '" + kBodyFormat + "'");
  const long long version = h5::read_int_attribute(file, "version");
  if (version < 1 || version > kBodyFormatVersion)
    throw h5::Failure("attribute 'version' is " + std::to_string(version) +
                      ", this evas reads versions 1 to " + std::to_string(kBodyFormatVersion));
  // Version 2: a reduced body (a subset of the nodes, no mass matrix).
  if (version >= 2 && h5::has_attribute(file, "reduced")) {
    const long long r = h5::read_int_attribute(file, "reduced");
    if (r != 0 && r != 1) throw h5::Failure("attribute 'reduced' must be 0 or 1");
    if (r == 1) {
      if (!h5::has_attribute(file, "full_num_nodes"))
        throw h5::Failure("attribute 'full_num_nodes' is missing (required when reduced = 1)");
      body.full_num_nodes = static_cast<long>(h5::read_int_attribute(file, "full_num_nodes"));
      if (body.full_num_nodes < 1) throw h5::Failure("attribute 'full_num_nodes' must be >= 1");
    }
  }
  if (!text[1]) throw h5::Failure("attribute 'name' is missing");
  body.name = *text[1];
  if (text[2] && *text[2] != "m")
    throw h5::Failure("attribute 'length_unit' is '" + *text[2] + "', only 'm' is supported");
  if (text[3] && *text[3] != "kg")
    throw h5::Failure("attribute 'mass_unit' is '" + *text[3] + "', only 'kg' is supported");

  // Nodes.
  std::vector<hsize_t> dims;
  const std::vector<long long> ids = read_int64s(file, "/nodes/ids", dims);
  if (dims.size() != 1)
    throw h5::Failure("dataset '/nodes/ids' has shape " + shape_text(dims) + ", expected (N,)");
  const hsize_t N = dims[0];
  if (N == 0)
    throw h5::Failure(
        "the body has no nodes ('/nodes/ids' is empty): a modal body needs the nodes its "
        "mode shapes are given at");
  body.node_ids.assign(ids.begin(), ids.end());
  // the ids in order: repeats are neighbours, and a set's members are found by
  // bisection (a block has thousands of nodes)
  std::vector<long> sorted_ids(body.node_ids);
  std::sort(sorted_ids.begin(), sorted_ids.end());
  if (const auto rep = repeat_in_sorted(sorted_ids))
    throw h5::Failure("dataset '/nodes/ids' repeats node id " + std::to_string(*rep));
  const std::vector<hsize_t> w_xyz = {N, 3}, w_N = {N}, w_N1 = {N + 1};
  const std::vector<double> xyz = read_doubles(file, "/nodes/coordinates", dims, &w_xyz);
  expect_finite("/nodes/coordinates", xyz);
  body.s = Eigen::Map<const RowMat>(xyz.data(), static_cast<Eigen::Index>(N), 3);

  // Mass.
  const int iN = static_cast<int>(N);
  if (body.reduced()) {
    if (h5::exists(file, "/mass"))
      throw h5::Failure("group '/mass' must be absent in a reduced body (reduced = 1)");
    if (body.full_num_nodes < static_cast<long>(N))
      throw h5::Failure("attribute 'full_num_nodes' is " + std::to_string(body.full_num_nodes) +
                        ", less than the " + std::to_string(N) + " nodes stored");
  } else if (h5::exists(file, "/mass/lumped") && h5::exists(file, "/mass/consistent")) {
    throw h5::Failure(
        "both '/mass/lumped' and '/mass/consistent' are present: give exactly one mass matrix");
  } else if (h5::exists(file, "/mass/lumped")) {
    body.mass.resize(iN, iN);
    const std::vector<double> m = read_doubles(file, "/mass/lumped", dims, &w_N);
    expect_finite("/mass/lumped", m);
    std::vector<Triplet> trips;
    for (int i = 0; i < iN; ++i) {
      if (m[i] < 0.0)
        throw h5::Failure("dataset '/mass/lumped' has a negative mass at node " +
                          std::to_string(body.node_ids[i]));
      trips.emplace_back(i, i, m[i]);
    }
    body.mass.setFromTriplets(trips.begin(), trips.end());
  } else if (h5::exists(file, "/mass/consistent")) {
    body.mass.resize(iN, iN);
    const std::vector<long long> indptr = read_int64s(file, "/mass/consistent/indptr", dims, &w_N1);
    const std::vector<long long> indices = read_int64s(file, "/mass/consistent/indices", dims);
    if (dims.size() != 1)
      throw h5::Failure("dataset '/mass/consistent/indices' must be one-dimensional");
    const hsize_t nnz = dims[0];
    const std::vector<hsize_t> w_nnz = {nnz};
    const std::vector<double> values = read_doubles(file, "/mass/consistent/values", dims, &w_nnz);
    expect_finite("/mass/consistent/values", values);
    if (indptr[0] != 0 || indptr[N] != static_cast<long long>(nnz))
      throw h5::Failure("dataset '/mass/consistent/indptr' must start at 0 and end at " +
                        std::to_string(nnz) + " (the number of values)");
    std::vector<Triplet> trips;
    for (hsize_t r = 0; r < N; ++r) {
      if (indptr[r + 1] < indptr[r])
        throw h5::Failure("dataset '/mass/consistent/indptr' decreases at row " +
                          std::to_string(r));
      for (long long k = indptr[r]; k < indptr[r + 1]; ++k) {
        if (indices[k] < 0 || indices[k] >= static_cast<long long>(N))
          throw h5::Failure("dataset '/mass/consistent/indices' has column " +
                            std::to_string(indices[k]) + " outside 0.." + std::to_string(N - 1));
        trips.emplace_back(static_cast<int>(r), static_cast<int>(indices[k]), values[k]);
      }
    }
    body.mass.setFromTriplets(trips.begin(), trips.end());
  } else {
    throw h5::Failure(
        "mass is missing: expected dataset '/mass/lumped' or group '/mass/consistent'");
  }
  body.mass.makeCompressed();

  // Modes.
  const std::vector<double> lambda = read_doubles(file, "/modes/eigenvalues", dims);
  if (dims.size() != 1)
    throw h5::Failure("dataset '/modes/eigenvalues' has shape " + shape_text(dims) +
                      ", expected (n,)");
  const hsize_t n = dims[0];
  expect_finite("/modes/eigenvalues", lambda);
  body.eigenvalues = Eigen::Map<const Vec>(lambda.data(), static_cast<Eigen::Index>(n));
  const std::vector<hsize_t> w_shapes = {3 * N, n}, w_n = {n};
  const std::vector<double> shapes = read_doubles(file, "/modes/shapes", dims, &w_shapes);
  expect_finite("/modes/shapes", shapes);
  assign_row_major(body.modes, shapes, static_cast<Eigen::Index>(3 * N),
                   static_cast<Eigen::Index>(n));
  const std::vector<double> damping = read_doubles(file, "/modes/damping", dims, &w_n);
  expect_finite("/modes/damping", damping);
  body.damping = Eigen::Map<const Vec>(damping.data(), static_cast<Eigen::Index>(n));
  const std::vector<long long> kinds = read_int64s(file, "/modes/kind", dims, &w_n);
  for (hsize_t k = 0; k < n; ++k) {
    if (kinds[k] != 0 && kinds[k] != 1)
      throw h5::Failure("dataset '/modes/kind' has value " + std::to_string(kinds[k]) +
                        " for mode " + std::to_string(k) + " (0 rigid, 1 elastic)");
    body.kinds.push_back(kinds[k] == 0 ? ModeKind::Rigid : ModeKind::Elastic);
  }

  // Node sets (optional group).
  if (h5::exists(file, "/sets")) {
    h5::Handle g = h5::open_group(file, "/sets");
    for (const std::string& name : h5::list_links(g)) {
      const std::string path = "/sets/" + name;
      const std::vector<long long> set = read_int64s(file, path, dims);
      if (dims.size() != 1) throw h5::Failure("dataset '" + path + "' must be one-dimensional");
      for (long long id : set)
        if (!std::binary_search(sorted_ids.begin(), sorted_ids.end(), static_cast<long>(id)))
          throw h5::Failure("dataset '" + path + "' names node " + std::to_string(id) +
                            ", which is not in '/nodes/ids'");
      std::vector<long long> members(set);
      std::sort(members.begin(), members.end());
      if (const auto rep = repeat_in_sorted(members))
        throw h5::Failure("dataset '" + path + "' repeats node id " + std::to_string(*rep));
      body.node_sets[name].assign(set.begin(), set.end());
    }
  }

  // Surface sets (optional group): areas and normals of mesh-face node sets.
  if (h5::exists(file, "/surfaces")) {
    h5::Handle g = h5::open_group(file, "/surfaces");
    for (const std::string& name : h5::list_links(g)) {
      const std::string path = "/surfaces/" + name;
      if (!body.node_sets.count(name))
        throw h5::Failure("group '" + path + "' has no node set '/sets/" + name + "'");
      const std::vector<long long> ids = read_int64s(file, path + "/nodes", dims);
      if (dims.size() != 1)
        throw h5::Failure("dataset '" + path + "/nodes' must be one-dimensional");
      const hsize_t ns = dims[0];
      for (long long id : ids)
        if (!std::binary_search(sorted_ids.begin(), sorted_ids.end(), static_cast<long>(id)))
          throw h5::Failure("dataset '" + path + "/nodes' names node " + std::to_string(id) +
                            ", which is not in '/nodes/ids'");
      const std::vector<hsize_t> want_area = {ns}, want_normal = {ns, 3};
      const std::vector<double> area = read_doubles(file, path + "/area", dims, &want_area);
      const std::vector<double> normal = read_doubles(file, path + "/normal", dims, &want_normal);
      SurfaceSet sf;
      sf.nodes.assign(ids.begin(), ids.end());
      sf.area = Eigen::Map<const Vec>(area.data(), static_cast<Eigen::Index>(ns));
      sf.normal = Eigen::Map<const RowMat>(normal.data(), static_cast<Eigen::Index>(ns), 3);
      try {
        sf.validate("surface set '" + name + "'");
      } catch (const InputError& e) {
        throw h5::Failure(std::string("group '") + path + "': " + e.what());
      }
      body.surfaces.emplace(name, std::move(sf));
    }
  }

  if (version >= 2) read_stored(file, body);
  if (body.reduced() && (!body.invariants || !body.mass_props))
    throw h5::Failure(std::string("group '") +
                      (body.invariants ? "/mass_properties" : "/invariants") +
                      "' is missing (required in a reduced body)");
  return body;
}

}  // namespace

void write_body_file(const std::string& path, const ModalBody& body) {
  try {
    body.validate();
  } catch (const InputError& e) {
    throw InputError(path + ": cannot write body: " + e.what());
  }
  h5::Quiet quiet;
  try {
    h5::Handle file = h5::create_file(path);
    write_body(file, body);
    if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0) throw h5::Failure("cannot flush the file");
  } catch (const h5::Failure& e) {
    throw InputError(path + ": " + e.what());
  }
}

ModalBody read_body_file(const std::string& path) {
  ModalBody body;
  {
    h5::Quiet quiet;
    try {
      h5::Handle file = h5::open_file(path);
      body = read_body(file);
    } catch (const h5::Failure& e) {
      throw InputError(path + ": " + e.what());
    }
  }
  body.source = path;
  try {
    body.validate();
  } catch (const InputError& e) {
    throw InputError(path + ": " + e.what());
  }
  return body;
}

}  // namespace evas
