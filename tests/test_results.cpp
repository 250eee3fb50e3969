// Results files: round trip, partial files after a failure, non-finite values
// rejected, summary JSON and CSV export.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "hdf5_heap.h"
#include "integrators/settings.h"
#include "io/results.h"

using namespace evas;

namespace {

std::string tmp_path(const std::string& name) {
  return ::testing::TempDir() + "evas_test_results_" + name;
}

ResultsWriter::Options options(int flush_rows = 256) {
  ResultsWriter::Options o;
  o.scene_text = "name: test\n# a comment with \"quotes\"\n";
  o.integrator = "ida";
  o.grid = "time";
  o.flush_rows = flush_rows;
  o.flush_seconds = 1e9;  // only row-count flushes: deterministic tests
  return o;
}

std::vector<Channel> two_channels() { return {{"a.px", "m"}, {"k1.force_x", "N"}}; }

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A completed file of eight rows of two_channels(), flushed every four.
void write_eight_rows(const std::string& path) {
  ResultsWriter w(path, two_channels(), options(4));
  for (int i = 0; i < 8; ++i) w.append(1e-3 * i, {1.0, 2.0});
  w.finish(IntegratorStats{}, "completed");
}

}  // namespace

TEST(Results, RoundTrip) {
  const std::string path = tmp_path("roundtrip.h5");
  IntegratorStats st;
  st.steps = 123;
  st.wall_seconds = 0.5;
  {
    ResultsWriter w(path, two_channels(), options(7));
    for (int i = 0; i < 50; ++i) w.append(1e-3 * i, {std::sin(0.1 * i), 10.0 * i});
    EXPECT_EQ(w.rows(), 50);
    w.finish(st, "completed");
  }
  const ResultsData d = read_results(path);
  ASSERT_EQ(d.time.size(), 50u);
  ASSERT_EQ(d.values.rows(), 50);
  ASSERT_EQ(d.values.cols(), 2);
  EXPECT_EQ(d.names, (std::vector<std::string>{"a.px", "k1.force_x"}));
  EXPECT_EQ(d.units, (std::vector<std::string>{"m", "N"}));
  EXPECT_EQ(d.status, "completed");
  EXPECT_EQ(d.integrator, "ida");
  EXPECT_EQ(d.grid, "time");
  EXPECT_EQ(d.scene, options().scene_text);
  for (int i = 0; i < 50; ++i) {
    EXPECT_EQ(d.time[i], 1e-3 * i);
    EXPECT_EQ(d.values(i, 0), std::sin(0.1 * i));
    EXPECT_EQ(d.values(i, 1), 10.0 * i);
  }
  h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  h5::Handle g(H5Gopen2(f, "/stats", H5P_DEFAULT), H5Gclose);
  EXPECT_EQ(h5::read_int_attribute(g, "steps"), 123);
  EXPECT_EQ(h5::read_double_attribute(g, "wall_seconds"), 0.5);
}

// The datasets are written without filters unless asked (Options::compress);
// with it, shuffle + deflate where the HDF5 library has deflate. Either way the
// values read back exactly.
TEST(Results, CompressionOnlyWhenAsked) {
  for (bool compress : {false, true}) {
    const std::string path = tmp_path(compress ? "deflate.h5" : "plain.h5");
    {
      ResultsWriter::Options o = options(16);
      o.compress = compress;
      ResultsWriter w(path, two_channels(), o);
      for (int i = 0; i < 40; ++i) w.append(1e-3 * i, {std::cos(0.3 * i), -2.0 * i});
      w.finish(IntegratorStats{}, "completed");
    }
    const ResultsData d = read_results(path);
    ASSERT_EQ(d.values.rows(), 40);
    for (int i = 0; i < 40; ++i) EXPECT_EQ(d.values(i, 0), std::cos(0.3 * i)) << compress;
    h5::Handle f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    for (const char* name : {"/time", "/channels/values"}) {
      h5::Handle ds(H5Dopen2(f, name, H5P_DEFAULT), H5Dclose);
      h5::Handle pl(H5Dget_create_plist(ds), H5Pclose);
      const int filters = H5Pget_nfilters(pl);
      if (!compress) {
        EXPECT_EQ(filters, 0) << name;
      } else if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
        EXPECT_EQ(filters, 2) << name;  // shuffle, deflate
      }
    }
  }
}

TEST(Results, PartialFileAfterFailure) {
  // The writer is destroyed without finish(): everything appended is readable
  // and the status says the run never completed.
  const std::string path = tmp_path("partial.h5");
  {
    ResultsWriter w(path, two_channels(), options(4));
    for (int i = 0; i < 10; ++i) w.append(0.1 * i, {1.0 * i, -1.0 * i});
  }
  const ResultsData d = read_results(path);
  EXPECT_EQ(d.time.size(), 10u);
  EXPECT_EQ(d.values(9, 1), -9.0);
  EXPECT_EQ(d.status, "running");
}

TEST(Results, RowsFlushedBeforeDestructionAreOnDisk) {
  // While the writer is alive, flushed rows can be read by another opener.
  const std::string path = tmp_path("live.h5");
  ResultsWriter w(path, two_channels(), options(5));
  for (int i = 0; i < 12; ++i) w.append(0.1 * i, {1.0, 2.0});
  const ResultsData d = read_results(path);
  EXPECT_EQ(d.time.size(), 10u);  // two full blocks of 5 flushed, 2 rows still buffered
}

TEST(Results, NonFiniteRejected) {
  const std::string path = tmp_path("nan.h5");
  {
    ResultsWriter w(path, two_channels(), options(100));
    w.append(0.0, {1.0, 2.0});
    w.append(0.5, {1.5, 2.5});
    try {
      w.append(0.75, {0.0, std::nan("")});
      FAIL() << "NaN accepted";
    } catch (const RunError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("k1.force_x"), std::string::npos) << msg;
      EXPECT_NE(msg.find("0.75"), std::string::npos) << msg;
    }
    EXPECT_THROW(w.append(1.0, {INFINITY, 0.0}), RunError);
    // Rows before the bad one are already on disk.
    EXPECT_EQ(read_results(path).time.size(), 2u);
    w.finish(IntegratorStats{}, "failed: channel 'k1.force_x' is NaN");
  }
  const ResultsData d = read_results(path);
  ASSERT_EQ(d.time.size(), 2u);
  EXPECT_TRUE(d.values.allFinite());
  EXPECT_EQ(d.status, "failed: channel 'k1.force_x' is NaN");
}

TEST(Results, CsvExport) {
  const std::string path = tmp_path("csv.h5");
  {
    ResultsWriter w(path, two_channels(), options());
    w.append(0.0, {0.25, -1.0});
    w.append(0.001, {0.5, 3e5});
    w.finish(IntegratorStats{}, "completed");
  }
  const std::string csv = tmp_path("out.csv");
  export_csv(path, csv);
  EXPECT_EQ(read_text(csv), "time[s],a.px[m],k1.force_x[N]\n0,0.25,-1\n0.001,0.5,300000\n");
}

TEST(Results, SummaryJson) {
  RunSummary s;
  s.scene = "two \"beams\"";
  s.integrator = "ida";
  s.status = "completed";
  s.t_end = 0.1;
  s.t_reached = 0.1;
  s.channels = two_channels();
  s.channel_summary = {{-1.0, 2.0, 1.5, 10}, {0.0, 0.0, 0.0, 0}};
  const std::string path = tmp_path("summary.json");
  write_summary_json(path, s);
  const std::string text = read_text(path);
  EXPECT_NE(text.find("\"scene\": \"two \\\"beams\\\"\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"status\": \"completed\""), std::string::npos);
  EXPECT_NE(text.find("\"name\": \"a.px\", \"unit\": \"m\", \"min\": -1, \"max\": 2, \"rms\": 1.5"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\"min\": null"), std::string::npos);
  // the build the results come from (CMakeLists.txt sets it: x86-64 or x86-64-v3)
  EXPECT_NE(text.find(std::string("\"build_arch\": \"") + build_arch() + "\""), std::string::npos)
      << text;
  EXPECT_STRNE(build_arch(), "unknown");
  // settings IDA does not read are named (its declaration, integrators/ida.cpp:
  // rho_inf is generalized-alpha's, method cvode's, anderson_depth the Newmark
  // family's), those it reads are not
  EXPECT_NE(text.find("\"settings_not_read\": [\"step\", \"min_step\", \"step_control\", "
                      "\"iteration\", \"anderson_depth\", \"balance_tol\", "
                      "\"max_iterations\", \"method\", \"table\", \"imex\", \"rho_inf\"]"),
            std::string::npos)
      << text;
}

TEST(Results, SettingsNotReadByEachMethod) {
  auto has = [](const std::vector<std::string>& v, const std::string& k) {
    return std::find(v.begin(), v.end(), k) != v.end();
  };
  const auto ga = settings_not_read_by("generalized-alpha");
  EXPECT_TRUE(has(ga, "max_steps") && has(ga, "jacobian_age") && has(ga, "method"));
  EXPECT_FALSE(has(ga, "rho_inf") || has(ga, "step") || has(ga, "rtol") || has(ga, "atol"));
  EXPECT_FALSE(has(ga, "anderson_depth"));     // read with iteration=anderson
  EXPECT_TRUE(has(ga, "baumgarte_beta"));      // index-1 is ida's
  EXPECT_FALSE(has(ga, "penalty_stiffness"));  // every method takes the penalty form
  const auto cv = settings_not_read_by("cvode");
  EXPECT_TRUE(has(cv, "rho_inf") && has(cv, "jacobian_age") && !has(cv, "method"));
  EXPECT_TRUE(has(cv, "anderson_depth") && has(cv, "baumgarte_alpha"));
  EXPECT_TRUE(settings_not_read_by("my-plugin").empty());
}

// The reason a setting has no effect, from the integrators' declarations of
// what they read (integrator_capabilities) and the table's conditions: the
// method, or a condition on another setting (evas run warns with it, evas
// study refuses a case key no case reads).
TEST(Results, UnreadSettingsAreNamedWithTheReason) {
  struct Check {
    const char *name, *linear_solver, *iteration, *formulation, *key, *reason;
  };
  const Check checks[] = {
      {"ida", "klu", "default", "default", "step",
       "ida does not read it (generalized-alpha, linear-acceleration, radau, hht-alpha, newmark, "
       "central-difference, arkode, bathe do)"},
      {"ida", "klu", "default", "default", "rho_inf",
       "ida does not read it (generalized-alpha, bathe do)"},
      {"ida", "klu", "default", "default", "rtol", ""},
      {"ida", "klu", "default", "default", "max_steps", ""},
      {"ida", "klu", "default", "default", "jacobian_age",
       "it is read only with linear_solver=second-order (here: klu)"},
      {"ida", "second-order", "default", "default", "jacobian_age", ""},
      {"ida", "klu", "anderson", "default", "anderson_depth",
       "ida does not read it (generalized-alpha, linear-acceleration, hht-alpha, newmark, "
       "central-difference do, with "
       "iteration=anderson)"},
      {"cvode", "second-order", "default", "default", "jacobian_age",
       "cvode does not read it (ida does, with linear_solver=second-order)"},
      {"linear-acceleration", "klu", "default", "default", "anderson_depth",
       "it is read only with iteration=anderson (here: default)"},
      {"linear-acceleration", "klu", "anderson", "default", "anderson_depth", ""},
      {"generalized-alpha", "klu", "default", "default", "baumgarte_beta",
       "generalized-alpha does not read it (ida does, with formulation=index-1)"},
      {"ida", "klu", "default", "default", "baumgarte_beta",
       "it is read only with formulation=index-1 (here: default)"},
      {"ida", "klu", "default", "index-1", "baumgarte_beta", ""},
      {"my-plugin", "klu", "default", "default", "rho_inf", ""},  // a plug-in's own
  };
  for (const Check& c : checks) {
    IntegratorSettings s;
    s.name = c.name;
    s.linear_solver = c.linear_solver;
    set_integrator_setting(s, "iteration", c.iteration);
    s.formulation = c.formulation;
    EXPECT_EQ(setting_unread_reason(s, c.key), c.reason) << c.name << " " << c.key;
  }
  EXPECT_THROW(setting_unread_reason(IntegratorSettings{}, "rtoll"), InputError);
}

// An integrator that declares what it reads is held to its declaration; one
// that declares nothing (a plug-in's default) is never warned about.
TEST(Results, DeclaredReadsOfARegisteredIntegrator) {
  IntegratorCapabilities caps;
  caps.declared = true;
  caps.adaptive = true;
  caps.reads = {"rtol", "atol", "max_steps"};
  register_integrator(
      "test-declared", [] { return make_integrator("ida"); }, "ida under another name", caps);
  register_integrator("test-undeclared", [] { return make_integrator("ida"); });
  IntegratorSettings s;
  s.name = "test-declared";
  EXPECT_EQ(setting_unread_reason(s, "rtol"), "");
  EXPECT_EQ(setting_unread_reason(s, "rho_inf"),
            "test-declared does not read it (generalized-alpha, bathe do)");
  const auto unread = settings_not_read_by("test-declared");
  EXPECT_NE(std::find(unread.begin(), unread.end(), "step"), unread.end());
  EXPECT_EQ(std::find(unread.begin(), unread.end(), "max_steps"), unread.end());
  EXPECT_FALSE(has_fixed_step("test-declared"));
  s.name = "test-undeclared";
  EXPECT_EQ(setting_unread_reason(s, "rho_inf"), "");
  EXPECT_TRUE(settings_not_read_by("test-undeclared").empty());
  EXPECT_FALSE(integrator_capabilities("test-undeclared").declared);
  // the built-in ones declare their kind
  EXPECT_TRUE(has_fixed_step("radau") && has_fixed_step("generalized-alpha"));
  EXPECT_FALSE(has_fixed_step("ida") || has_fixed_step("cvode"));
  EXPECT_EQ(integrator_capabilities("ida").formulations.front(), "ggl");
}

TEST(Results, ReadErrorsNameTheFile) {
  try {
    read_results(tmp_path("nothing.h5"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.h5"), std::string::npos);
  }
}

TEST(Results, DeclaredShapeBeyondTheStoredDataIsRefused) {
  // A corrupt results file whose /time declares 10^12 rows (the extendible
  // dataset grown without data): a clear error before any allocation.
  const std::string path = tmp_path("huge_dims.h5");
  write_eight_rows(path);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, "/time", H5P_DEFAULT);
  ASSERT_GE(d, 0);
  const hsize_t huge[1] = {1000000000000ULL};
  ASSERT_GE(H5Dset_extent(d, huge), 0);
  H5Dclose(d);
  H5Fclose(f);
  try {
    read_results(path);
    FAIL() << "a 10^12-row /time was read";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("huge_dims.h5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("declares"), std::string::npos) << msg;
  }
}

// A results file whose first global-heap object (the variable-length strings:
// attributes, channel names and units) claims 2^31 bytes: libhdf5 1.10.8 copies
// past its buffer on such a read, which ended the process by SIGSEGV. The read
// now runs in a child process (io/isolated_read.h): a clear error naming the
// file, and this process goes on.
TEST(Results, CorruptHeapObjectIsRefusedNotACrash) {
  const std::string path = tmp_path("heap.h5");
  write_eight_rows(path);
  test_hdf5::corrupt_first_heap_object_size(path, std::uint64_t{1} << 31);
  try {
    read_results(path);
    FAIL() << "a corrupt heap object was read";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("heap.h5"), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot be read"), std::string::npos) << msg;
  }
}
