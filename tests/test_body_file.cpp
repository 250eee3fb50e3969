// Modal-body HDF5 files: round trip (lumped and consistent mass) and clear
// errors for missing, malformed, truncated and foreign files.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "hdf5_heap.h"
#include "io/body_file.h"
#include "io/hdf5_util.h"

using namespace evas;

namespace {

// Three nodes on a line, two modes (one "rigid", one "elastic"); values are
// arbitrary but valid: the file layer does not care about physics.
ModalBody small_body(bool consistent) {
  ModalBody b;
  b.name = consistent ? "consistent-body" : "lumped-body";
  b.node_ids = {10, 20, 30};
  b.s.resize(3, 3);
  b.s << 0.0, 0.0, 0.0, 0.5, 0.1, -0.2, 1.0, 0.0, 0.3;
  b.mass.resize(3, 3);
  std::vector<Triplet> t = {{0, 0, 2.0}, {1, 1, 3.0}, {2, 2, 1.5}};
  if (consistent) {
    t.push_back({0, 1, 0.25});
    t.push_back({1, 0, 0.25});
    t.push_back({1, 2, 0.125});
    t.push_back({2, 1, 0.125});
  }
  b.mass.setFromTriplets(t.begin(), t.end());
  b.mass.makeCompressed();
  b.modes.resize(9, 2);
  for (int r = 0; r < 9; ++r) {
    b.modes(r, 0) = 0.1 * (r % 3 == 0);
    b.modes(r, 1) = std::sin(0.7 * r + 0.2);
  }
  b.eigenvalues.resize(2);
  b.eigenvalues << 0.0, 4.0e6;
  b.damping.resize(2);
  b.damping << 0.0, 40.0;
  b.kinds = {ModeKind::Rigid, ModeKind::Elastic};
  b.node_sets["end0"] = {10};
  b.node_sets["ends"] = {10, 30};
  return b;
}

std::string tmp_path(const std::string& name) {
  return ::testing::TempDir() + "evas_test_body_" + name;
}

void expect_same(const ModalBody& a, const ModalBody& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.node_ids, b.node_ids);
  EXPECT_EQ(a.s, b.s);
  EXPECT_EQ(Mat(a.mass), Mat(b.mass));
  EXPECT_EQ(a.eigenvalues, b.eigenvalues);
  EXPECT_EQ(a.modes, b.modes);
  EXPECT_EQ(a.damping, b.damping);
  EXPECT_EQ(a.kinds, b.kinds);
  EXPECT_EQ(a.node_sets, b.node_sets);
}

// Expects read_body_file to throw InputError mentioning every fragment.
void expect_error(const std::string& path, const std::vector<std::string>& fragments) {
  try {
    read_body_file(path);
    FAIL() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments)
      EXPECT_NE(msg.find(f), std::string::npos) << "message '" << msg << "' lacks '" << f << "'";
  }
}

// Opens a written file and lets the test damage it.
template <class Fn>
void edit_file(const std::string& path, Fn&& fn) {
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
  ASSERT_TRUE(f.valid());
  fn(f.get());
}

}  // namespace

TEST(BodyFile, RoundTripLumped) {
  const ModalBody b = small_body(false);
  const std::string path = tmp_path("lumped.h5");
  write_body_file(path, b);
  expect_same(b, read_body_file(path));
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  EXPECT_TRUE(h5::exists(f, "/mass/lumped"));
  EXPECT_FALSE(h5::exists(f, "/mass/consistent"));
  EXPECT_EQ(h5::read_string_attribute(f, "format"), "evas-modal-body");
  EXPECT_EQ(h5::read_int_attribute(f, "version"), 2);  // version 1 files are read too
  EXPECT_EQ(h5::read_int_attribute(f, "reduced"), 0);
  EXPECT_FALSE(h5::exists(f, "/invariants"));  // only when the body carries them
}

TEST(BodyFile, RoundTripConsistent) {
  const ModalBody b = small_body(true);
  const std::string path = tmp_path("consistent.h5");
  write_body_file(path, b);
  expect_same(b, read_body_file(path));
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  EXPECT_TRUE(h5::exists(f, "/mass/consistent/indptr"));
  EXPECT_FALSE(h5::exists(f, "/mass/lumped"));
}

// A body of the size where other evas files are compressed is stored
// contiguous (io/body_file.cpp: inflating modal data cost 5 % of an engine
// run for 15 % of file size) and reads back exactly; a file whose datasets are
// compressed (written by an evas before 2026-11-26, or by h5repack) reads the same.
TEST(BodyFile, LargeBodyIsContiguousAndExact) {
  ModalBody b;
  b.name = "big";
  const int N = 400, n = 12;
  b.s.resize(N, 3);
  b.mass.resize(N, N);
  std::vector<Triplet> t;
  for (int i = 0; i < N; ++i) {
    b.node_ids.push_back(1000 + i);
    b.s.row(i) << 0.01 * i, std::cos(i), std::sin(i);
    t.emplace_back(i, i, 0.5 + 0.001 * i);
  }
  b.mass.setFromTriplets(t.begin(), t.end());
  b.modes = Mat::Random(3 * N, n);
  b.eigenvalues = Vec::LinSpaced(n, 1e3, 1e7);
  b.damping = Vec::Constant(n, 3.0);
  b.kinds.assign(n, ModeKind::Elastic);
  const std::string path = tmp_path("big.h5");
  write_body_file(path, b);
  expect_same(b, read_body_file(path));
  auto layout = [&](int* filters) {
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    h5::Handle d(H5Dopen2(f, "/modes/shapes", H5P_DEFAULT), H5Dclose);
    h5::Handle p(H5Dget_create_plist(d), H5Pclose);
    *filters = H5Pget_nfilters(p);
    return H5Pget_layout(p);
  };
  int filters = -1;
  EXPECT_EQ(layout(&filters), H5D_CONTIGUOUS);
  EXPECT_EQ(filters, 0);

  edit_file(path, [&](hid_t f) {
    H5Ldelete(f, "/modes/shapes", H5P_DEFAULT);
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = b.modes;
    h5::write_doubles(f, "/modes/shapes", {3 * N, n}, rows.data(), true);
  });
  EXPECT_EQ(layout(&filters), H5D_CHUNKED);
  EXPECT_GE(filters, 2);
  expect_same(b, read_body_file(path));
}

TEST(BodyFile, MissingFile) {
  expect_error(tmp_path("does-not-exist.h5"), {"does-not-exist.h5", "missing"});
}

TEST(BodyFile, NotHdf5) {
  const std::string path = tmp_path("text.h5");
  std::ofstream(path) << "this is not an HDF5 file\n";
  expect_error(path, {"text.h5", "not an HDF5 file"});
}

TEST(BodyFile, Truncated) {
  const std::string path = tmp_path("full.h5");
  write_body_file(path, small_body(true));
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = tmp_path("truncated.h5");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expect_error(cut, {"truncated.h5"});
}

TEST(BodyFile, WrongFormatAttribute) {
  const std::string path = tmp_path("format.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) { h5::write_attribute(f, "format", std::string("something")); });
  expect_error(path, {"format.h5", "attribute 'format'", "something"});
}

TEST(BodyFile, MissingDataset) {
  const std::string path = tmp_path("nodamping.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) { H5Ldelete(f, "/modes/damping", H5P_DEFAULT); });
  expect_error(path, {"nodamping.h5", "'/modes/damping'", "missing"});
}

TEST(BodyFile, MissingMass) {
  const std::string path = tmp_path("nomass.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) { H5Ldelete(f, "/mass/lumped", H5P_DEFAULT); });
  expect_error(path, {"nomass.h5", "/mass/lumped"});
}

TEST(BodyFile, WrongShape) {
  const std::string path = tmp_path("shape.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) {
    H5Ldelete(f, "/modes/shapes", H5P_DEFAULT);
    std::vector<double> v(8 * 2, 0.0);
    h5::write_doubles(f, "/modes/shapes", {8, 2}, v.data());
  });
  expect_error(path, {"shape.h5", "'/modes/shapes'", "(8 x 2)", "(9 x 2)"});
}

TEST(BodyFile, NonFiniteValue) {
  const std::string path = tmp_path("nan.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) {
    H5Ldelete(f, "/nodes/coordinates", H5P_DEFAULT);
    std::vector<double> v(9, 1.0);
    v[4] = std::nan("");
    h5::write_doubles(f, "/nodes/coordinates", {3, 3}, v.data());
  });
  expect_error(path, {"nan.h5", "'/nodes/coordinates'", "non-finite"});
}

TEST(BodyFile, BadModeKind) {
  const std::string path = tmp_path("kind.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) {
    H5Ldelete(f, "/modes/kind", H5P_DEFAULT);
    const int k[2] = {0, 7};
    h5::write_int32s(f, "/modes/kind", {2}, k);
  });
  expect_error(path, {"kind.h5", "'/modes/kind'", "7"});
}

// An attribute read into one value must hold one: a 'version' of four
// integers was read over the stack before (found by fuzzing, docs/fuzzing.md).
TEST(BodyFile, AttributeWithSeveralValues) {
  const std::string path = tmp_path("version4.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) {
    H5Adelete(f, "version");
    const hsize_t n = 4;
    h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    h5::Handle a(H5Acreate2(f, "version", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT),
                 H5Aclose);
    const long long v[4] = {2, 2, 2, 2};
    ASSERT_GE(H5Awrite(a, H5T_NATIVE_LLONG, v), 0);
  });
  expect_error(path, {"version4.h5", "attribute 'version'", "single value"});
}

// A dataset whose layout claims more bytes than the file holds is refused
// before anything is allocated for it. Here the data of '/nodes/ids' is said
// to lie in an external file of 80 MB that does not exist; HDF5 reports that
// size as the dataset's storage, so only the file's own size bounds it.
TEST(BodyFile, StorageLargerThanTheFile) {
  const std::string path = tmp_path("external.h5");
  write_body_file(path, small_body(false));
  edit_file(path, [](hid_t f) {
    H5Ldelete(f, "/nodes/ids", H5P_DEFAULT);
    const hsize_t n = 10'000'000;
    h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
    h5::Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    ASSERT_GE(H5Pset_external(dcpl, "evas-test-missing.bin", 0, n * 8), 0);
    h5::Handle d(H5Dcreate2(f, "/nodes/ids", H5T_STD_I64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                 H5Dclose);
    ASSERT_TRUE(d.valid());
    EXPECT_EQ(H5Dget_storage_size(d), n * 8);
  });
  expect_error(path, {"external.h5", "'/nodes/ids'", "the file stores only"});
}

// libhdf5 1.10.8 trusts a global-heap object's size when it reads a
// variable-length string: a size of 2^31 in a 10 kB file made it copy past its
// buffer, and evas ended by SIGSEGV (found by fuzz_body_file, docs/fuzzing.md).
// The read now runs in a child process (io/isolated_read.h): the file is
// refused with its name and the attribute, and the test process goes on.
TEST(BodyFile, CorruptHeapObjectIsRefusedNotACrash) {
  for (const std::uint64_t size : {std::uint64_t{1} << 31, std::uint64_t{1} << 62}) {
    const std::string path = tmp_path("heap.h5");
    write_body_file(path, small_body(false));
    test_hdf5::corrupt_first_heap_object_size(path, size);
    expect_error(path, {"heap.h5", "'format'", "cannot be read", "corrupt file?"});
  }
  // the same file undamaged still reads (the strings come back from the child)
  const std::string path = tmp_path("heap_ok.h5");
  write_body_file(path, small_body(false));
  EXPECT_EQ(read_body_file(path).name, small_body(false).name);
}
