// The bad-input catalogue (tests/data/bad/catalogue.tsv): every row runs the
// real `evas` binary on one bad input (a scene, a body file, a pressure table,
// a CalculiX file or a command line) and checks that it is refused the way a
// user should see it: the expected exit code, the expected message fragments,
// no raw C++ exception text on stderr, and no death by a signal.
//
// The rows run in a temporary copy of tests/data/bad, which also receives the
// generated inputs (gen_*): HDF5 body files written with the project's own
// writer and HDF5 helpers (binary files are awkward to keep in the tree), and
// scene files too large to keep. Nothing is written into the source tree.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <thread>

#include "bodies/body_builder.h"
#include "bodies/reduce_body.h"
#include "bodies/truss.h"
#include "io/body_file.h"
#include "io/hdf5_util.h"
#include "model/invariants.h"

using namespace evas;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = fs::path(EVAS_SOURCE_DIR) / "tests" / "data";
const fs::path kCatalogue = kSource / "bad" / "catalogue.tsv";

struct Row {
  std::string name, args;
  int code = 0;
  std::vector<std::string> fragments;
  int line = 0;
};

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == '\t') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

std::vector<Row> load_catalogue() {
  std::vector<Row> rows;
  std::ifstream in(kCatalogue);
  std::string line;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> f = split_tabs(line);
    Row r;
    r.line = no;
    r.name = f[0];
    if (f.size() >= 3) {
      r.args = f[1];
      r.code = std::atoi(f[2].c_str());
      r.fragments.assign(f.begin() + 3, f.end());
    } else {
      r.code = -1;  // malformed: reported by the test
    }
    rows.push_back(r);
  }
  return rows;
}

// --- generated inputs ---------------------------------------------------------

using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// 12 nodes (a 2-bay truss), 6 rigid + 6 elastic modes: modes 0-5 rigid, 6-11 elastic.
ModalBody base_body() {
  TrussBeamSpec spec;
  spec.segments = 2;
  spec.length = 0.2;
  spec.width = 0.04;
  BuildOptions opt;
  opt.num_elastic = 6;
  return build_modal_body("beam", make_truss_beam(spec), opt);
}

// Opens a written body file and lets `fn` damage it with the HDF5 C API.
template <class Fn>
void edit(const fs::path& path, Fn&& fn) {
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose);
  ASSERT_TRUE(f.valid()) << path;
  fn(f.get());
}

void replace_doubles(hid_t f, const std::string& name, const std::vector<hsize_t>& dims,
                     const double* data) {
  H5Ldelete(f, name.c_str(), H5P_DEFAULT);
  h5::write_doubles(f, name, dims, data);
}

void replace_int64s(hid_t f, const std::string& name, const std::vector<hsize_t>& dims,
                    const long long* data) {
  H5Ldelete(f, name.c_str(), H5P_DEFAULT);
  h5::write_int64s(f, name, dims, data);
}

// A chunked dataset that declares `dims` but stores nothing.
void declare_unstored(hid_t f, const std::string& name, std::vector<hsize_t> dims, hid_t type) {
  H5Ldelete(f, name.c_str(), H5P_DEFAULT);
  std::vector<hsize_t> maxdims(dims.size(), H5S_UNLIMITED), chunk(dims.size(), 1);
  chunk[0] = 1024;
  h5::Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data()),
                   H5Sclose);
  h5::Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data());
  h5::Handle d(H5Dcreate2(f, name.c_str(), type, space, H5P_DEFAULT, plist, H5P_DEFAULT), H5Dclose);
  ASSERT_TRUE(d.valid()) << name;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Every gen_* input of the catalogue, written into `dir`.
void generate_inputs(const fs::path& dir) {
  const ModalBody ok = base_body();
  const hsize_t N = static_cast<hsize_t>(ok.num_nodes()), n = static_cast<hsize_t>(ok.num_modes());
  auto write = [&](const std::string& name, const ModalBody& b) {
    write_body_file((dir / ("gen_" + name + ".h5")).string(), b);
    return dir / ("gen_" + name + ".h5");
  };
  write("ok", ok);
  {  // shapes not mass-normalised
    ModalBody b = ok;
    b.modes.col(8) *= 1.01;
    write("not_normalised", b);
  }
  {  // normalised, but modes 8 and 9 not mass-orthogonal
    ModalBody b = ok;
    b.modes.col(8) = (ok.modes.col(8) + 0.01 * ok.modes.col(9)) / std::sqrt(1.0001);
    write("not_orthogonal", b);
  }
  {  // an elastic mode marked rigid (eigenvalue and damping set to 0)
    ModalBody b = ok;
    b.kinds[7] = ModeKind::Rigid;
    b.eigenvalues[7] = 0.0;
    b.damping[7] = 0.0;
    write("elastic_marked_rigid", b);
  }
  {  // an elastic mode marked rigid, its eigenvalue kept
    ModalBody b = ok;
    b.kinds[6] = ModeKind::Rigid;
    write("elastic_marked_rigid_lambda", b);
  }
  {  // a rigid mode with a non-zero eigenvalue
    ModalBody b = ok;
    b.eigenvalues[0] = 0.5 * ok.eigenvalues[6];
    write("rigid_with_eigenvalue", b);
  }
  {  // a rigid mode with a negative eigenvalue beyond round-off
    ModalBody b = ok;
    b.eigenvalues[0] = -0.01 * ok.eigenvalues[11];
    write("negative_rigid_eigenvalue", b);
  }
  {  // an all-zero shape
    ModalBody b = ok;
    b.modes.col(8).setZero();
    write("zero_shape", b);
  }
  write("zero_modes", ok.select_modes({}));
  {  // duplicate ids in a node set
    ModalBody b = ok;
    b.node_sets["dup"] = {1, 1, 2};
    write("duplicate_set_ids", b);
  }
  {  // reduced (v2) bodies: a good one, one whose stored invariants are not normalised
    ModalBody full = ok;
    store_full_body_data(full);
    ReduceOptions opt;
    opt.all_sets = false;
    opt.keep_sets = {"end0", "end1"};
    const ModalBody red = reduce_body(full, opt);
    write("reduced_ok", red);
    ModalBody bad = red;
    auto inv = std::make_shared<ModalInvariants>(*red.invariants);
    inv->M[0][0](8, 8) += 0.05;
    bad.invariants = inv;
    write("reduced_not_normalised", bad);
    // a full body whose stored mass properties disagree with its nodes
    ModalBody mismatch = full;
    mismatch.mass_props->mass *= 1.01;
    write("stored_mismatch", mismatch);
  }

  // Damaged files (the writer refuses to write these).
  RowMat shapes = ok.modes;
  RowMat xyz = ok.s;
  auto damaged = [&](const std::string& name, auto&& fn) { edit(write(name, ok), fn); };
  damaged("negative_elastic_eigenvalue", [&](hid_t f) {
    Vec lam = ok.eigenvalues;
    lam[7] = -5.0;
    replace_doubles(f, "/modes/eigenvalues", {n}, lam.data());
  });
  damaged("both_masses", [&](hid_t f) {
    h5::Handle g = h5::create_group(f, "/mass/consistent");
    std::vector<long long> indptr, indices;
    std::vector<double> values;
    for (hsize_t i = 0; i <= N; ++i) indptr.push_back(static_cast<long long>(i));
    for (hsize_t i = 0; i < N; ++i) {
      indices.push_back(static_cast<long long>(i));
      values.push_back(ok.mass.coeff(static_cast<int>(i), static_cast<int>(i)));
    }
    h5::write_int64s(g, "indptr", {N + 1}, indptr.data());
    h5::write_int64s(g, "indices", {N}, indices.data());
    h5::write_doubles(g, "values", {N}, values.data());
  });
  damaged("nan_shape", [&](hid_t f) {
    RowMat s = shapes;
    s(5, 7) = std::nan("");
    replace_doubles(f, "/modes/shapes", {3 * N, n}, s.data());
  });
  damaged("inf_eigenvalue", [&](hid_t f) {
    Vec lam = ok.eigenvalues;
    lam[9] = HUGE_VAL;
    replace_doubles(f, "/modes/eigenvalues", {n}, lam.data());
  });
  damaged("nan_coordinates", [&](hid_t f) {
    RowMat s = xyz;
    s(3, 1) = std::nan("");
    replace_doubles(f, "/nodes/coordinates", {N, 3}, s.data());
  });
  damaged("huge_dims",
          [&](hid_t f) { declare_unstored(f, "/nodes/ids", {10000000000ULL}, H5T_STD_I64LE); });
  damaged("big_unstored_dims",
          [&](hid_t f) { declare_unstored(f, "/nodes/ids", {100000000ULL}, H5T_STD_I64LE); });
  damaged("big_shapes_dims", [&](hid_t f) {
    declare_unstored(f, "/modes/shapes", {30000000ULL, n}, H5T_IEEE_F64LE);
  });
  damaged("duplicate_node_ids", [&](hid_t f) {
    std::vector<long long> ids(ok.node_ids.begin(), ok.node_ids.end());
    ids[1] = ids[0];
    replace_int64s(f, "/nodes/ids", {N}, ids.data());
  });
  damaged("zero_nodes", [&](hid_t f) {  // every node-sized array empty, no sets
    replace_int64s(f, "/nodes/ids", {0}, nullptr);
    replace_doubles(f, "/nodes/coordinates", {0, 3}, nullptr);
    replace_doubles(f, "/modes/shapes", {0, n}, nullptr);
    replace_doubles(f, "/mass/lumped", {0}, nullptr);
    H5Ldelete(f, "/sets", H5P_DEFAULT);
  });
  damaged("missing_damping", [&](hid_t f) { H5Ldelete(f, "/modes/damping", H5P_DEFAULT); });
  damaged("wrong_shape", [&](hid_t f) {
    replace_doubles(f, "/modes/shapes", {3 * N - 1, n}, shapes.data());
  });
  damaged("bad_kind", [&](hid_t f) {
    std::vector<long long> kinds;
    for (ModeKind k : ok.kinds) kinds.push_back(static_cast<long long>(k));
    kinds[3] = 2;
    replace_int64s(f, "/modes/kind", {n}, kinds.data());
  });
  damaged("negative_mass", [&](hid_t f) {
    Vec m = ok.mass.diagonal();
    m[1] = -1.0;
    replace_doubles(f, "/mass/lumped", {N}, m.data());
  });
  damaged("bad_format",
          [&](hid_t f) { h5::write_attribute(f, "format", std::string("something-else")); });
  {  // the first 40 % of a good file
    std::ifstream in(dir / "gen_ok.h5", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write_text(dir / "gen_truncated.h5", bytes.substr(0, bytes.size() * 2 / 5));
  }

  // Scenes too large to keep in the tree.
  const std::string head =
      "name: big\nbodies:\n  - name: beam\n    generate: {type: truss-beam, segments: 2}\n"
      "    modes: {elastic: 2}\n";
  {
    std::string t = head + "markers:\n  - {name: m, body: beam, nodes: [";
    for (int i = 0; i < 1000001; ++i) t += "1,";
    t.back() = ']';
    write_text(dir / "gen_long_list.yaml", t + "}\ntime: {end: 0.001}\n");
  }
  {
    std::string t = head + "markers: [";
    for (int i = 0; i < 100001; ++i) t += "{},";
    t.back() = ']';
    write_text(dir / "gen_many_markers.yaml", t + "\ntime: {end: 0.001}\n");
  }
  // A scene of 17 MiB (a sparse file: the size is refused before reading).
  write_text(dir / "gen_too_large.yaml", head + "time: {end: 0.001}\n");
  fs::resize_file(dir / "gen_too_large.yaml", 17u << 20);
  // A pressure table of 65 MiB (sparse) and a scene that reads it.
  write_text(dir / "gen_table_too_large.txt", "# unit: bar\n0 1.0\n");
  fs::resize_file(dir / "gen_table_too_large.txt", 65u << 20);
  {
    std::string t = slurp(dir / "piston_missing_table.yaml");
    const std::string from = "no_such_table.txt";
    t.replace(t.find(from), from.size(), "gen_table_too_large.txt");
    write_text(dir / "gen_piston_table_too_large.yaml", t);
  }
}

// The folder the rows run in: a copy of tests/data/bad plus the generated
// inputs, made once per test process and removed at its end.
// The gen_* inputs are written on first use only (ctest runs every row as a
// process of its own).
class Workspace : public ::testing::Environment {
 public:
  static fs::path dir;
  static bool generated;
  void SetUp() override {
    dir = fs::path(::testing::TempDir()) / ("evas_bad_inputs_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const auto& e : fs::directory_iterator(kSource / "bad"))
      if (e.is_regular_file()) fs::copy_file(e.path(), dir / e.path().filename());
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  // Writes the generated inputs when `args` (or a file it names) refers to one.
  static void prepare(const std::string& args) {
    if (generated) return;
    bool needed = args.find("gen_") != std::string::npos;
    std::istringstream is(args);
    for (std::string word; !needed && is >> word;) {
      const fs::path p = dir / word;
      if (word.find('/') == std::string::npos && fs::is_regular_file(p))
        needed = slurp(p).find("gen_") != std::string::npos;
    }
    if (!needed) return;
    generate_inputs(dir);
    generated = true;
  }
};
fs::path Workspace::dir;
bool Workspace::generated = false;

const auto* const kWorkspace = ::testing::AddGlobalTestEnvironment(new Workspace);

// --- running evas ---------------------------------------------------------------

fs::path evas_binary() {
  return fs::canonical("/proc/self/exe").parent_path().parent_path() / "evas";
}

std::string substitute(std::string s, const std::string& key, const std::string& value) {
  for (auto pos = s.find(key); pos != std::string::npos; pos = s.find(key, pos + value.size()))
    s.replace(pos, key.size(), value);
  return s;
}

struct Outcome {
  bool exited = false, signaled = false, timed_out = false;
  int code = -1, signal = 0;
  std::string out, err;
};

// Runs `evas ARGS` through /bin/sh in `cwd` (stdin /dev/null), with a time limit.
Outcome run_evas(const std::string& args, const fs::path& cwd, const std::string& tag) {
  const std::string command = "exec '" + evas_binary().string() + "' " + args;
  const std::string out_path = (cwd / (".out_" + tag)).string();
  const std::string err_path = (cwd / (".err_" + tag)).string();
  Outcome o;
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(cwd.c_str()) != 0) ::_exit(126);
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || err < 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  if (pid < 0) return o;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int status = 0;
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      o.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  o.exited = WIFEXITED(status);
  o.code = o.exited ? WEXITSTATUS(status) : -1;
  o.signaled = WIFSIGNALED(status);
  o.signal = o.signaled ? WTERMSIG(status) : 0;
  o.out = slurp(out_path);
  o.err = slurp(err_path);
  fs::remove(out_path);
  fs::remove(err_path);
  return o;
}

// gtest prints a failing parameter with this (the row, not its bytes).
void PrintTo(const Row& r, std::ostream* os) { *os << "catalogue.tsv:" << r.line << " " << r.name; }

class BadInput : public ::testing::TestWithParam<Row> {};

TEST_P(BadInput, IsRefusedClearly) {
  const Row& row = GetParam();
  ASSERT_GE(row.code, 0) << "catalogue.tsv:" << row.line << ": malformed row";
  const std::string args = substitute(row.args, "{calculix}", (kSource / "calculix").string());
  Workspace::prepare(args);
  ASSERT_FALSE(HasFatalFailure());
  // every row starts without an earlier row's results (a run refuses a folder
  // that holds them, docs/errors.md)
  std::error_code ec;
  fs::remove_all(Workspace::dir / "out", ec);
  const Outcome o = run_evas(args, Workspace::dir, row.name);
  const std::string both = o.out + o.err;
  if (std::getenv("EVAS_BAD_INPUTS_VERBOSE"))  // prints every message, for review
    std::cout << "evas " << args << "  -> exit " << o.code << "\n" << o.err;
  SCOPED_TRACE("catalogue.tsv:" + std::to_string(row.line) + ": evas " + args + "\n--- stderr:\n" +
               o.err.substr(0, 4000));
  EXPECT_FALSE(o.timed_out) << "evas did not finish within 60 s";
  EXPECT_FALSE(o.signaled) << "evas was killed by signal " << o.signal;
  EXPECT_TRUE(o.exited);
  EXPECT_EQ(o.code, row.code);
  for (const std::string& f : row.fragments)
    EXPECT_NE(both.find(f), std::string::npos) << "output lacks '" << f << "'";
  for (const char* raw : {"std::", "basic_string", "_M_", "bad_alloc", "terminate called",
                          "what():", "Assertion", "runtime_error"})
    EXPECT_EQ(o.err.find(raw), std::string::npos) << "stderr shows raw C++ text '" << raw << "'";
  if (row.code != 0) {
    EXPECT_FALSE(both.empty()) << "a refused input must say why";
  }
}

std::string row_name(const ::testing::TestParamInfo<Row>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInput, ::testing::ValuesIn(load_catalogue()), row_name);

TEST(BadInputCatalogue, IsLargeAndConsistent) {
  const std::vector<Row> rows = load_catalogue();
  EXPECT_GE(rows.size(), 60u);
  std::set<std::string> names;
  std::string all_args;
  for (const Row& r : rows) {
    EXPECT_TRUE(names.insert(r.name).second) << "row name repeated: " << r.name;
    EXPECT_FALSE(r.fragments.empty() && r.code != 0) << r.name << ": no expected message";
    for (char c : r.name) EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    all_args += r.args + "\n";
  }
  // Every file of the catalogue folder is used: named by a row or by a scene.
  std::string scenes;
  for (const auto& e : fs::directory_iterator(kSource / "bad"))
    if (e.path().extension() == ".yaml") scenes += slurp(e.path());
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(kSource / "bad")) {
    const std::string f = e.path().filename().string();
    if (f == "catalogue.tsv") continue;
    ++files;
    EXPECT_TRUE(all_args.find(f) != std::string::npos || scenes.find(f) != std::string::npos)
        << "tests/data/bad/" << f << " is not used by any row";
  }
  EXPECT_GE(files, 60u);
}

}  // namespace
