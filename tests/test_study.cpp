// `evas study` (study/): case-grid expansion, scene overrides, the error
// measure, and the three studies on a one-mass oscillator scene: a rigid truss
// body on an undamped spring to ground.
//
// The oscillator: the spring acts at the marker on the middle cross-section of
// a 2-bay truss beam, whose node centroid is the body's centre of mass (the
// alternating bracing is symmetric about the middle), so only the three rigid
// translations are loaded. The rigid modes are mass-normalised, q = sqrt(m) x,
// so a spring k on the translation gives qdd + (k/m) q = 0: omega = sqrt(k/m)
// with m the body's total mass.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bodies/truss.h"
#include "integrators/settings.h"
#include "io/hdf5_util.h"
#include "io/outputs.h"
#include "io/results.h"
#include "io/scene.h"
#include "model/modal_body.h"
#include "plot/figures.h"
#include "solver/system.h"
#include "study/expression.h"
#include "study/study.h"

using namespace evas;
using namespace evas::study;
namespace fs = std::filesystem;

namespace {

// A work folder below the system's temporary directory, removed at the end.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static int serial = 0;
    path_ = fs::temp_directory_path() / ("evas_study_" + tag + "_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(serial++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = path_ / name;
    std::ofstream(p) << text;
    return p.string();
  }

 private:
  fs::path path_;
};

// The oscillator body: its spec is the scene's `generate` block.
TrussBeamSpec oscillator_spec() {
  TrussBeamSpec s;
  s.segments = 2;
  s.length = 0.2;
  s.width = 0.05;
  s.area = 1e-4;
  s.density = 7850.0;
  return s;
}

double oscillator_mass() {
  const FeModel fe = make_truss_beam(oscillator_spec());
  return mass_properties(fe.s, fe.Ms).mass;
}

const double kStiffness = 2.0e5;  // [N/m]

double oscillator_omega() { return std::sqrt(kStiffness / oscillator_mass()); }

// Undamped spring-mass scene; `t_end` and `out_step` [s]. The body starts at
// rest at the spring's free length with 0.1 m/s along the first rigid mode.
std::string oscillator_scene(double t_end, double out_step) {
  std::ostringstream os;
  os << "name: oscillator\n"
        "bodies:\n"
        "  - name: mass\n"
        "    generate: {type: truss-beam, segments: 2, length: 0.2, width: 0.05, area: 1e-4, "
        "density: 7850}\n"
        "    modes: {rigid: true, elastic: 0}\n"
        "    initial: {q: [0, 0, 0, 0, 0, 0], v: [0.1, 0, 0, 0, 0, 0]}\n"
        "markers:\n"
        "  - {name: c, body: mass, set: section1}\n"
        "  - {name: g, ground: [0.1, 0, 0]}\n"
        "elements:\n"
        "  - {name: spring, type: spring-damper, markers: [g, c], stiffness: ["
     << kStiffness << ", " << kStiffness << ", " << kStiffness
     << "], damping: [0, 0, 0]}\n"
        "integrator: {name: ida, rtol: 1e-6, atol: 1e-10}\n"
        "time: {start: 0, end: "
     << t_end
     << "}\n"
        "output:\n"
        "  grid: time\n"
        "  step: "
     << out_step
     << "\n"
        "  channels:\n"
        "    - {marker: c}\n"
        "    - {element: spring}\n";
  return os.str();
}

Options quiet_options(const std::string& scene, const fs::path& out) {
  Options o;
  o.scene = scene;
  o.out_dir = out.string();
  o.plot = false;
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

}  // namespace

// --- case grid ---------------------------------------------------------------

TEST(StudyCaseGrid, ListsExpandToTheCartesianProductFirstKeySlowest) {
  IntegratorSettings base;
  base.atol = 1e-9;  // the scene's block: kept where the spec is silent
  const auto cases = expand_case("generalized-alpha step=2e-5,1e-5 rho_inf=0.5,0.8,1", base);
  ASSERT_EQ(cases.size(), 6u);
  EXPECT_EQ(cases[0].settings.name, "generalized-alpha");
  EXPECT_DOUBLE_EQ(cases[0].settings.step, 2e-5);
  EXPECT_DOUBLE_EQ(cases[0].settings.rho_inf, 0.5);
  EXPECT_DOUBLE_EQ(cases[1].settings.rho_inf, 0.8);
  EXPECT_DOUBLE_EQ(cases[2].settings.rho_inf, 1.0);
  EXPECT_DOUBLE_EQ(cases[3].settings.step, 1e-5);
  EXPECT_DOUBLE_EQ(cases[3].settings.rho_inf, 0.5);
  for (const auto& c : cases) {
    EXPECT_DOUBLE_EQ(c.settings.atol, 1e-9);
    EXPECT_EQ(c.label, settings_label(c.settings));
    EXPECT_EQ(c.swept, (std::vector<std::string>{"step", "rho_inf"}));
  }
  EXPECT_EQ(cases[0].label, "generalized-alpha atol=1e-09 step=2e-05 rho_inf=0.5");
}

TEST(StudyCaseGrid, LogRangesAreInclusiveAndExact) {
  const auto cases = expand_case("ida rtol=1e-3..1e-7/5", IntegratorSettings{});
  ASSERT_EQ(cases.size(), 5u);
  const double want[] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(cases[i].settings.rtol, want[i]) << i;
  // a range mixed with a list; an integer setting is rounded without repeats
  EXPECT_EQ(expand_values("rtol", "1e-2..1e-4/3,5e-6"),
            (std::vector<std::string>{"1e-2", "0.001", "1e-4", "5e-6"}));
  EXPECT_EQ(expand_values("max_iterations", "1..4/6"),
            (std::vector<std::string>{"1", "2", "3", "4"}));
  // no NAME: the scene's integrator stays
  IntegratorSettings base;
  base.name = "cvode";
  const auto c = expand_case("method=bdf,adams", base);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[1].settings.name, "cvode");
  EXPECT_EQ(c[1].settings.method, "adams");
}

TEST(StudyCaseGrid, BadKeyValueOrRangeIsAnInputErrorNamingTheCase) {
  const IntegratorSettings base;
  std::string msg = input_error([&] { expand_case("ida rtoll=1e-3", base); });
  EXPECT_NE(msg.find("--case 'ida rtoll=1e-3'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'rtoll' is not an integrator setting"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("ida rtol=1e-3,abc", base); });
  EXPECT_NE(msg.find("--case 'ida rtol=1e-3,abc'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'abc' is not a number"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("ida rtol=2", base); });
  EXPECT_NE(msg.find("rtol: 2 must be"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("euler step=1e-3", base); });
  EXPECT_NE(msg.find("'euler' is unknown"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("cvode method=bdf..adams/2", base); });
  EXPECT_NE(msg.find("needs a numeric setting"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("ida rtol=1e-3..1e-5", base); });
  EXPECT_NE(msg.find("A..B/N"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("ida rtol=0..1e-5/3", base); });
  EXPECT_NE(msg.find("> 0"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("ida rtol", base); });
  EXPECT_NE(msg.find("not KEY=VALUES"), std::string::npos) << msg;
  msg = input_error([&] { expand_case("ida rtol=1e-3,", base); });
  EXPECT_NE(msg.find("empty value"), std::string::npos) << msg;
  // a cases file names file and line
  TempDir dir("cases");
  const std::string f = dir.write("cases.txt", "# header\nida rtol=1e-3  # first\n\ncvode x=1\n");
  const auto lines = read_cases_file(f);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].first, "ida rtol=1e-3");
  msg = input_error([&] { expand_case(lines[1].first, base, lines[1].second); });
  EXPECT_NE(msg.find("cases.txt:4: case 'cvode x=1'"), std::string::npos) << msg;
}

// A key the case's method does not read would give every value the same run
// under a different label: a convergence or work-precision study that
// measures nothing. It is refused, unless some case of the spec reads it.
TEST(StudyCaseGrid, AKeyNoCaseReadsIsAnInputError) {
  const IntegratorSettings base;
  std::string msg = input_error([&] { expand_case("ida step=1e-5,2e-5", base); });
  EXPECT_NE(msg.find("--case 'ida step=1e-5,2e-5': 'step': ida does not read it "
                     "(generalized-alpha, linear-acceleration, radau, hht-alpha, newmark, "
                     "central-difference, arkode, bathe do)"),
            std::string::npos)
      << msg;
  msg = input_error([&] { expand_case("radau rtol=1e-4 max_steps=100", base); });
  EXPECT_NE(msg.find("'max_steps': radau does not read it (ida, cvode, arkode do)"),
            std::string::npos)
      << msg;
  msg = input_error([&] { expand_case("linear-acceleration anderson_depth=2,4", base); });
  EXPECT_NE(msg.find("'anderson_depth': it is read only with iteration=anderson (here: default)"),
            std::string::npos)
      << msg;
  // read by the anderson cases of the grid: kept, in every case
  const auto c =
      expand_case("linear-acceleration iteration=fixed-point,anderson anderson_depth=2", base);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[1].settings.iteration, Iteration::anderson);
  EXPECT_EQ(c[1].settings.anderson_depth, 2);
}

TEST(StudyCaseGrid, GlobMatch) {
  EXPECT_TRUE(glob_match("main*.fx", "main1.fx"));
  EXPECT_TRUE(glob_match("*", ""));
  EXPECT_TRUE(glob_match("m?in*", "main12"));
  EXPECT_FALSE(glob_match("main*.fx", "main1.fy"));
  EXPECT_FALSE(glob_match("main", "main1"));
}

// --- scene overrides -----------------------------------------------------------

TEST(StudyOverrides, ElementGlobAndTimeEndChangeTheScene) {
  TempDir dir("override");
  std::string text = oscillator_scene(0.01, 1e-3);
  // a second spring so that the glob matches two elements
  const std::string extra =
      "  - {name: spring2, type: spring-damper, markers: [g, c], stiffness: [1, 1, 1]}\n";
  text.insert(text.find("integrator:"), extra);
  const std::string path = dir.write("osc.yaml", text);
  const SceneSource src =
      load_scene_source(path,
                        {"spring*.damping=[5, 6, 7]", "mass.lof={kind: fixed, origin: [0, 0, 1]}",
                         "mass.initial.v=[0.2, 0, 0, 0, 0, 0]"},
                        0.02);
  const Scene s = src.parse();
  EXPECT_DOUBLE_EQ(s.t_end, 0.02);
  EXPECT_EQ(s.model->elements().size(), 2u);
  EXPECT_NE(src.text.find("damping: [5, 6, 7]"), std::string::npos) << src.text;
  std::size_t count = 0;
  for (std::size_t p = src.text.find("[5, 6, 7]"); p != std::string::npos;
       p = src.text.find("[5, 6, 7]", p + 1))
    ++count;
  EXPECT_EQ(count, 2u);
  EXPECT_NE(src.text.find("origin: [0, 0, 1]"), std::string::npos) << src.text;
  EXPECT_DOUBLE_EQ(s.model->bodies()[0].v0[0], 0.2);
  // without overrides the text is kept as written
  EXPECT_EQ(load_scene_source(path, {}).text, text);
  // a value the scene reader rejects is reported by the scene reader
  const SceneSource bad = load_scene_source(path, {"spring.stiffness=7"});
  std::string msg = input_error([&] { bad.parse(); });
  EXPECT_NE(msg.find("stiffness"), std::string::npos) << msg;
}

TEST(StudyOverrides, UnknownItemIsAnInputErrorNamingIt) {
  TempDir dir("override_bad");
  const std::string path = dir.write("osc.yaml", oscillator_scene(0.01, 1e-3));
  std::string msg = input_error([&] { load_scene_source(path, {"main*.clearance=5e-5"}); });
  EXPECT_NE(msg.find("--param 'main*.clearance=5e-5'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no body, marker or element named 'main*'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("known: mass, c, g, spring"), std::string::npos) << msg;
  msg = input_error([&] { load_scene_source(path, {"spring=1"}); });
  EXPECT_NE(msg.find("ITEM.KEY=VALUE"), std::string::npos) << msg;
}

// --- error measure ---------------------------------------------------------------

TEST(StudyMeasure, ErrorIsRelativeToEachChannelsAmplitude) {
  const int nt = 100;  // whole periods: the means are 5 and 0
  Mat ref(nt, 3), y(nt, 3);
  std::vector<double> time(nt);
  for (int i = 0; i < nt; ++i) {
    time[i] = 0.01 * i;
    ref(i, 0) = 5.0 + 2.0 * std::sin(2 * M_PI * time[i]);  // mean ~5, amplitude 2
    ref(i, 1) = 1e3 * std::cos(2 * M_PI * time[i]);        // amplitude 1e3
    ref(i, 2) = 7.0;                                       // constant: left out
    y(i, 0) = ref(i, 0) + 0.02;                            // 1 % of channel 0's amplitude
    y(i, 1) = ref(i, 1) + (i == 50 ? 30.0 : 0.0);          // 3 % at one time
    y(i, 2) = 8.0;
  }
  std::vector<int> all = window_rows(parse_window("all"), time, {});
  const auto amp = amplitudes(ref, all);
  EXPECT_NEAR(amp[0], 2.0, 1e-9);
  EXPECT_NEAR(amp[1], 1e3, 1e-9);
  EXPECT_EQ(amp[2], 0.0);
  EXPECT_NEAR(relative_error(y, ref, all, Norm::Max), 0.03, 1e-12);
  // rms: channel 0 constant 1 %, channel 1 a single 3 % spike -> 0.03 / sqrt(100)
  EXPECT_NEAR(relative_error(y, ref, all, Norm::Rms), 0.01, 1e-12);
  // a time window that leaves the spike out
  const auto early = window_rows(parse_window("0:0.4"), time, {});  // 0.4 s = row 40
  EXPECT_EQ(early.size(), 41u);
  EXPECT_NEAR(relative_error(y, ref, early, Norm::Max), 0.01 * 2.0 / amplitudes(ref, early)[0],
              1e-12);
  // a run with fewer rows than the window has no error
  EXPECT_TRUE(std::isnan(relative_error(y.topRows(50), ref, all, Norm::Max)));
  // last-cycles on a crank-angle grid (1 degree steps): the last 720 rows
  std::vector<double> angle(2000), t2(2000);
  for (int i = 0; i < 2000; ++i) angle[i] = t2[i] = i;
  const auto last = window_rows(parse_window("last-cycles=1"), t2, angle);
  ASSERT_EQ(last.size(), 720u);
  EXPECT_EQ(last.front(), 1280);
  EXPECT_EQ(window_rows(parse_window("last-cycles=2"), t2, angle).size(), 1440u);
  const std::string short_msg =
      input_error([&] { window_rows(parse_window("last-cycles=3"), t2, angle); });
  EXPECT_NE(short_msg.find("less than 2160"), std::string::npos) << short_msg;
  EXPECT_NE(
      input_error([&] { window_rows(parse_window("last-cycles=1"), t2, {}); }).find("crank-angle"),
      std::string::npos);
  EXPECT_NE(input_error([] { parse_window("last"); }).find("expected all"), std::string::npos);
  // channel selection
  const std::vector<Channel> ch = {
      {"crank_angle", "deg"}, {"main1.fx", "N"}, {"main1.fy", "N"}, {"main2.fx", "N"}};
  EXPECT_EQ(select_channels(ch, ""), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(select_channels(ch, "main*.fx"), (std::vector<int>{1, 3}));
  const std::string msg = input_error([&] { select_channels(ch, "cyl*"); });
  EXPECT_NE(msg.find("available: crank_angle, main1.fx"), std::string::npos) << msg;
  // joints: residuals out by default, multipliers in; any of them by name
  const std::vector<Channel> cj = {{"k.fx", "N"},
                                   {"pin.p.x.g", ""},
                                   {"pin.p.x.g_dot", ""},
                                   {"pin.p.x.lambda", ""},
                                   {"rig.g", ""}};
  EXPECT_EQ(select_channels(cj, ""), (std::vector<int>{0, 3}));
  EXPECT_EQ(select_channels(cj, "pin.*.g"), (std::vector<int>{1}));
}

// The measures of --norm on two units: a force channel that swings 1e3 N, one
// that barely moves (1e-2 N), and a displacement of 1e-3 m. Every expected
// value follows from the definitions in study/measure.h by hand.
TEST(StudyMeasure, EveryNormOnAGroupWithAStillChannel) {
  const int nt = 100;
  Mat ref(nt, 3), y(nt, 3);
  for (int i = 0; i < nt; ++i) {
    const double s = std::sin(2 * M_PI * 0.01 * i);
    ref(i, 0) = 1e3 * s;         // N, amplitude 1e3
    ref(i, 1) = 1e-2 * s;        // N, amplitude 1e-2: still beside channel 0
    ref(i, 2) = 1e-3 * s;        // m, amplitude 1e-3
    y(i, 0) = ref(i, 0) + 1.0;   // 1e-3 of its amplitude
    y(i, 1) = ref(i, 1) + 1e-3;  // 0.1 of its own amplitude, 1e-6 of the group's
    y(i, 2) = ref(i, 2) + 2e-6;  // 2e-3 of its amplitude
  }
  y(nt - 1, 0) += 4.0;  // the last time: channel 0 off by 5
  std::vector<int> all(nt);
  for (int i = 0; i < nt; ++i) all[i] = i;
  const std::vector<std::string> units = {"N", "N", "m"};
  auto errs = [&](const std::string& norm) {
    return channel_errors(y, ref, all, parse_measure(norm), units);
  };
  // channel: the still channel sets the error (0.1)
  const auto ch = errs("channel");
  EXPECT_NEAR(ch.total, 0.1, 1e-9);
  EXPECT_EQ(ch.worst, 1);
  EXPECT_NEAR(errs("max").total, 0.1, 1e-9);
  // group: the still channel on 1e3 N (1e-6); channel 0's spike 5/1e3 sets it
  const auto gr = errs("group");
  EXPECT_NEAR(gr.error[1], 1e-6, 1e-12);
  EXPECT_NEAR(gr.error[2], 2e-3, 1e-12);
  EXPECT_NEAR(gr.total, 5e-3, 1e-12);
  EXPECT_EQ(gr.worst, 0);
  EXPECT_NEAR(gr.scale[1], 1e3, 1e-9);
  // floor=0.1: the still channel counts on 100 N
  const auto fl = errs("floor=0.1");
  EXPECT_NEAR(fl.error[1], 1e-5, 1e-12);
  EXPECT_NEAR(fl.error[2], 2e-3, 1e-12);
  EXPECT_NEAR(errs("floor=0").total, ch.total, 1e-15);
  // final: the last row only, on the group's amplitude
  const auto fi = errs("final");
  EXPECT_NEAR(fi.error[0], 5e-3, 1e-12);
  EXPECT_NEAR(fi.error[2], 2e-3, 1e-12);
  // l2: sqrt(sum d^2 / sum swing^2) per unit group
  double sw0 = 0, sw1 = 0, d0 = 0;
  for (int i = 0; i < nt; ++i) {
    sw0 += ref(i, 0) * ref(i, 0);
    sw1 += ref(i, 1) * ref(i, 1);
    d0 += (y(i, 0) - ref(i, 0)) * (y(i, 0) - ref(i, 0));
  }
  const auto l2 = errs("l2");
  EXPECT_NEAR(l2.error[0], std::sqrt(d0 / (sw0 + sw1)), 1e-12);
  EXPECT_NEAR(l2.error[1], std::sqrt(nt * 1e-6 / (sw0 + sw1)), 1e-15);
  // the m group (2e-6 / (1e-3 / sqrt(2)) = 2.8e-3) beats the N group (1.6e-3)
  EXPECT_NEAR(l2.error[2], 2e-6 * std::sqrt(2.0) / 1e-3, 1e-12);
  EXPECT_LT(std::hypot(l2.error[0], l2.error[1]), l2.error[2]);
  EXPECT_NEAR(l2.total, l2.error[2], 1e-15);
  EXPECT_EQ(l2.worst, 2);
  // rms on each channel's own amplitude
  EXPECT_NEAR(errs("rms").error[1], 0.1, 1e-9);
  // without units one group: the displacement counts on 1e3 as well
  EXPECT_NEAR(channel_errors(y, ref, all, parse_measure("group"), {}).error[2], 2e-9, 1e-15);
  // texts and bad values
  EXPECT_EQ(measure_text(parse_measure("floor=0.01")), "floor=0.01");
  EXPECT_EQ(measure_text(parse_measure("max")), "channel");
  EXPECT_EQ(std::string(kDefaultNorm), "group");
  EXPECT_NE(input_error([] { parse_measure("floor=2"); }).find("[0, 1]"), std::string::npos);
  EXPECT_NE(input_error([] { parse_measure("mean"); }).find("expected group, channel"),
            std::string::npos);
  EXPECT_NE(error_definition(parse_measure("l2"), parse_window("all")).find("--norm l2"),
            std::string::npos);
}

// Expressions of t for analytic references (study/expression.h).
TEST(StudyMeasure, ExpressionsOfTime) {
  EXPECT_DOUBLE_EQ(Expression("1 + 2 * 3", "x")(0.0), 7.0);
  EXPECT_DOUBLE_EQ(Expression("-2^2", "x")(0.0), -4.0);    // power binds tighter than minus
  EXPECT_DOUBLE_EQ(Expression("2^3^2", "x")(0.0), 512.0);  // right-associative
  EXPECT_DOUBLE_EQ(Expression("(1 + t) / 4", "x")(3.0), 1.0);
  EXPECT_NEAR(Expression("1e-3*sin(2*pi*50*t)", "x")(0.005), 1e-3, 1e-15);
  EXPECT_NEAR(Expression("exp(1) - e + sqrt(abs(-16)) + cos(0)", "x")(0.0), 5.0, 1e-15);
  EXPECT_NE(
      input_error([] { Expression("sin(t", "--reference-expr c.px"); }).find("')' is missing"),
      std::string::npos);
  EXPECT_NE(
      input_error([] { Expression("2 * foo(t)", "x"); }).find("unknown name 'foo' at column 5"),
      std::string::npos);
  EXPECT_NE(input_error([] { Expression("1 +", "x"); }).find("an operand is missing"),
            std::string::npos);
  EXPECT_NE(input_error([] { Expression("1 2", "x"); }).find("unexpected '2'"), std::string::npos);
}

// The oscillator against its closed form: the spring force is
// k (v0 / sqrt(m)) / omega sin(omega t) (v0 the rigid mode's velocity, the
// modes mass-normalised); generalized-alpha without dissipation is second order
// against it (Chung & Hulbert 1993).
TEST(StudyConvergence, AnalyticReferenceGivesTheOrder) {
  TempDir dir("analytic");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.02, 1e-3));
  Options o = quiet_options(scene, dir.path() / "ida");
  o.channels = "spring.fx";
  o.reference = "ida rtol=1e-12 atol=1e-16";
  const auto wp = work_precision(o, {{"ida rtol=1e-10", ""}});
  const double w = oscillator_omega(), amp = kStiffness * 0.1 / std::sqrt(oscillator_mass()) / w;
  // the sign of the channel: from the reference run a quarter period in
  const double tq = M_PI / (2 * w);
  const std::size_t kq = static_cast<std::size_t>(std::lround(tq / 1e-3));
  const double sign = wp.reference.y(static_cast<long>(kq), 0) > 0 ? 1.0 : -1.0;
  std::ostringstream expr;
  expr.precision(17);
  expr << "spring.fx=" << sign * amp << "*sin(" << w << "*t)";
  Options a = quiet_options(scene, dir.path() / "analytic");
  a.reference_exprs = {expr.str()};
  // the reference run itself is on the closed form to 1e-8
  const auto check = work_precision(a, {{"ida rtol=1e-12 atol=1e-16", ""}});
  ASSERT_EQ(check.cases[0].status, CaseStatus::completed) << check.cases[0].message;
  EXPECT_LT(check.cases[0].error, 1e-7);
  EXPECT_EQ(check.reference.description.rfind("analytic: spring.fx = ", 0), 0u)
      << check.reference.description;
  const auto res =
      convergence(a, {"generalized-alpha rho_inf=1 step_control=fixed rtol=1e-12 atol=1e-16 "
                      "step=4e-5,2e-5,1e-5",
                      ""});
  std::cout << "analytic reference: observed order " << res.slope << "\n";
  EXPECT_NEAR(res.slope, 2.0, 0.05);
  // bad expressions and names are input errors before any run
  a.reference_exprs = {"spring.fq=t"};
  EXPECT_NE(input_error([&] {
              convergence(a, {"ida rtol=1e-3,1e-4", ""});
            }).find("spring.fq"),
            std::string::npos);
  a.reference_exprs = {"spring.fx=sin(t"};
  EXPECT_NE(input_error([&] {
              convergence(a, {"ida rtol=1e-3,1e-4", ""});
            }).find("')' is missing"),
            std::string::npos);
}

// --- status text ---------------------------------------------------------------------

// The enums are written as these exact words (csv, md, h5, console).
TEST(StudyStatus, TextIsTheWordTheFilesHold) {
  EXPECT_STREQ(to_text(CaseStatus::not_run), "not run");
  EXPECT_STREQ(to_text(CaseStatus::completed), "completed");
  EXPECT_STREQ(to_text(CaseStatus::failed), "failed");
  EXPECT_EQ(RunData{}.status, CaseStatus::not_run);
  EXPECT_EQ(CaseResult{}.status, CaseStatus::not_run);
  EXPECT_STREQ(to_text(StabilityStatus::not_run), "not run");
  EXPECT_STREQ(to_text(StabilityStatus::bracketed), "bracketed");
  EXPECT_STREQ(to_text(StabilityStatus::stable_to_hmax), "stable up to HMAX");
  EXPECT_STREQ(to_text(StabilityStatus::unstable_at_hmin), "unstable at HMIN");
  EXPECT_STREQ(to_text(StabilityStatus::reference_failed), "reference failed");
  EXPECT_STREQ(to_text(StabilityStatus::interrupted), "interrupted");
  EXPECT_STREQ(to_text(StabilityStatus::timed_out), "timed out");
  EXPECT_EQ(StabilityPoint{}.status, StabilityStatus::not_run);
}

// --- work-precision ------------------------------------------------------------------

TEST(StudyWorkPrecision, FailedCaseIsRecordedAndTheOthersHaveFiniteErrors) {
  const auto t0 = std::chrono::steady_clock::now();
  TempDir dir("wp");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.05, 5e-4));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-9 atol=1e-13";
  o.plot = true;  // exercises the gnuplot script (the png only when gnuplot is installed)
  const auto res =
      work_precision(o, {{"ida rtol=1e-4,1e-6", ""},
                         {"cvode rtol=1e-5", ""},
                         {"generalized-alpha step=1e-4", ""},
                         {"linear-acceleration step=1e-4", ""},
                         {"generalized-alpha step=1e-3 max_iterations=1 step_control=fixed", ""}});
  ASSERT_EQ(res.cases.size(), 6u);
  EXPECT_FALSE(res.info.interrupted);
  for (std::size_t i = 0; i + 1 < res.cases.size(); ++i) {
    const auto& r = res.cases[i];
    EXPECT_EQ(r.status, CaseStatus::completed) << r.c.label << ": " << r.message;
    EXPECT_TRUE(std::isfinite(r.error)) << r.c.label;
    EXPECT_LT(r.error, 0.2) << r.c.label;
    EXPECT_GT(r.stats.steps, 0) << r.c.label;
    EXPECT_GT(r.wall, 0.0) << r.c.label;
  }
  EXPECT_LT(res.cases[1].error, res.cases[0].error);  // tighter tolerance, smaller error
  const auto& bad = res.cases.back();
  EXPECT_EQ(bad.status, CaseStatus::failed);
  EXPECT_FALSE(bad.message.empty());
  EXPECT_TRUE(std::isnan(bad.error));
  std::cout << "failed case: " << bad.c.label << ": " << bad.message << "\n";

  const fs::path out = dir.path() / "out";
  for (const char* f : {"study.csv", "study.md", "study.h5", "study.gp"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  // csv: header + one row per case, the failed one with its message
  std::ifstream csv(out / "study.csv");
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("label,integrator,rtol,", 0), 0u) << header;
  EXPECT_NE(header.find(",status,message,error,wall,"), std::string::npos) << header;
  EXPECT_NE(header.find(",residual_evals,"), std::string::npos) << header;
  int rows = 0;
  while (std::getline(csv, line)) ++rows, last = line;
  EXPECT_EQ(rows, 6);
  EXPECT_NE(last.find(",failed,"), std::string::npos) << last;
  // md: the table with the failed case's message
  std::ifstream mdf(out / "study.md");
  const std::string md((std::istreambuf_iterator<char>(mdf)), {});
  EXPECT_NE(md.find("| failed: "), std::string::npos) << md;
  EXPECT_NE(md.find("A_c = max over the window"), std::string::npos);
  // h5: the table and the reference
  {
    h5::Handle f = h5::open_file((out / "study.h5").string());
    EXPECT_EQ(h5::read_strings(f, "cases/status").back(), "failed");
    EXPECT_EQ(h5::read_strings(f, "cases/message").back(), bad.message);
    std::vector<hsize_t> dims;
    const auto err = h5::read_doubles(f, "cases/error", dims);
    ASSERT_EQ(err.size(), 6u);
    EXPECT_DOUBLE_EQ(err[0], res.cases[0].error);
    EXPECT_EQ(h5::read_strings(f, "cases/settings/step_control").back(), "fixed");
    h5::read_int64s(f, "cases/stats/residual_evals", dims);
    EXPECT_EQ(dims[0], 6u);
    h5::read_doubles(f, "reference/values", dims);
    ASSERT_EQ(dims.size(), 2u);
    EXPECT_EQ(dims[0], res.reference.time.size());
    EXPECT_EQ(dims[1], res.reference.names.size());
    EXPECT_EQ(h5::read_string_attribute(f, "study"), "work-precision");
    EXPECT_EQ(h5::read_string_attribute(f, "norm"), "group");
    h5::read_doubles(f, "cases/channel_error", dims);
    ASSERT_EQ(dims.size(), 2u);
    EXPECT_EQ(dims[1], res.reference.names.size());
  }
  // errors.csv: every case x channel, exactly one channel marked per completed
  // case, and it is the one study.csv names
  std::ifstream ef(out / "errors.csv");
  std::getline(ef, line);
  EXPECT_EQ(line, "case,label,channel,unit,scale,error,sets_error");
  std::vector<int> marked(6, 0);
  int erows = 0;
  while (std::getline(ef, line)) {
    ++erows;
    if (line.substr(line.size() - 2) == ",1") {
      const int k = std::stoi(line.substr(0, line.find(',')));
      ++marked[static_cast<std::size_t>(k)];
      EXPECT_NE(line.find("," + res.cases[static_cast<std::size_t>(k)].error_channel + ","),
                std::string::npos)
          << line;
    }
  }
  EXPECT_EQ(erows, static_cast<int>(6 * res.reference.names.size()));
  for (std::size_t k = 0; k + 1 < 6; ++k) EXPECT_EQ(marked[k], 1) << k;
  EXPECT_EQ(marked[5], 0);  // the failed case has no error
  const double s = seconds_since(t0);
  std::cout << "work-precision study: " << s << " s\n";
  EXPECT_LT(s, 20.0);
}

// The figure's legend leaves out the settings every curve shares (on the
// paper's engine the scene's linear solver made every entry so long that the
// legend covered the curves); the title names them once.
TEST(StudyWorkPrecision, LegendLeavesOutSettingsEveryCurveShares) {
  TempDir dir("wp_legend");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.05, 5e-4));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-9 atol=1e-13";
  o.plot = true;
  const auto res = work_precision(
      o, {{"ida rtol=1e-4,1e-6 max_steps=50000", ""}, {"cvode rtol=1e-5 max_steps=50000", ""}});
  ASSERT_EQ(res.cases.size(), 3u);
  std::ifstream in(dir.path() / "out" / "study.gp");
  const std::string gp((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(gp.find("; all curves: max_steps=50000"), std::string::npos) << gp;
  EXPECT_NE(gp.find("title 'ida'"), std::string::npos) << gp;
  EXPECT_NE(gp.find("title 'cvode'"), std::string::npos) << gp;
  std::istringstream lines(gp);
  int plots = 0;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("plot ", 0) == 0) {
      ++plots;
      EXPECT_EQ(line.find("max_steps"), std::string::npos) << line;  // in no legend entry
    }
  EXPECT_EQ(plots, 2);
  // `evas plot work-precision study.h5` draws the same figure again from the
  // file (one code, plot/study_figures.h): the script differs only in its output
  PlotOptions po;
  po.kind = "work-precision";
  const fs::path again = dir.path() / "again.png";
  plot_results((dir.path() / "out" / "study.h5").string(), po, again);
  std::ifstream in2(dir.path() / "again.gp");
  std::string gp2((std::istreambuf_iterator<char>(in2)), {});
  const std::string from = "set output 'study.png'", to = "set output 'again.png'";
  std::string expected = gp;
  ASSERT_NE(expected.find(from), std::string::npos);
  expected.replace(expected.find(from), from.size(), to);
  EXPECT_EQ(gp2, expected);
  EXPECT_TRUE(fs::exists(again));
  // a file that is no HDF5 file is named
  try {
    plot_results(scene, po, dir.path() / "x.png");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("osc.yaml: not an HDF5 file"), std::string::npos)
        << e.what();
  }
}

// A study of the scene changed by --param carries a name that says so, in its
// table, its file and its figure (the plain scene's name alone would pass the
// changed scene's answer for the plain one's).
TEST(StudyWorkPrecision, ParamsMarkTheSceneName) {
  TempDir dir("wp_params");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.05, 5e-4));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-8 atol=1e-12";
  o.params = {"spring.damping=[3, 3, 3]"};
  o.plot = true;
  const auto res = work_precision(o, {{"ida rtol=1e-4", ""}});
  EXPECT_EQ(res.info.scene_name, "oscillator with 1 --param");
  std::ifstream in(dir.path() / "out" / "study.md");
  const std::string md((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(md.rfind("# Work-precision study: oscillator with 1 --param\n", 0), 0u) << md;
  EXPECT_NE(md.find("with spring.damping=[3, 3, 3]"), std::string::npos) << md;
  std::ifstream g(dir.path() / "out" / "study.gp");
  const std::string gp((std::istreambuf_iterator<char>(g)), {});
  EXPECT_NE(gp.find("work-precision: oscillator with 1 --param"), std::string::npos) << gp;
  o.params.clear();
  o.out_dir = (dir.path() / "plain").string();
  EXPECT_EQ(work_precision(o, {{"ida rtol=1e-4", ""}}).info.scene_name, "oscillator");
}

TEST(StudyWorkPrecision, BadInputIsReportedBeforeAnyRun) {
  TempDir dir("wp_bad");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.01, 1e-3));
  Options o = quiet_options(scene, dir.path() / "out");
  EXPECT_NE(input_error([&] {
              work_precision(o, {{"ida rtol=x", ""}});
            }).find("--case"),
            std::string::npos);
  o.channels = "main*.fx";
  EXPECT_NE(input_error([&] {
              work_precision(o, {{"ida", ""}});
            }).find("spring.fx"),
            std::string::npos);
  o.channels = "";
  o.window = "last-cycles=1";
  EXPECT_NE(input_error([&] {
              work_precision(o, {{"ida", ""}});
            }).find("crank-angle"),
            std::string::npos);
  o.window = "";
  o.reference = "ida rtol=1e-9,1e-10";
  EXPECT_NE(input_error([&] {
              work_precision(o, {{"ida", ""}});
            }).find("single case"),
            std::string::npos);
  // a failing reference is not bad input
  o.reference = "ida max_steps=1";
  EXPECT_THROW(work_precision(o, {{"ida", ""}}), ReferenceFailed);
}

TEST(StudyWorkPrecision, ReferenceFileMatchesChannelsByNameAndTimes) {
  TempDir dir("wp_ref");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.02, 1e-3));
  // write a reference file the way `evas run` does, from the study's own run
  Options o = quiet_options(scene, dir.path() / "a");
  o.reference = "ida rtol=1e-10 atol=1e-14";
  const auto a = work_precision(o, {{"ida rtol=1e-5", ""}});
  {
    const SceneSource src = load_scene_source(scene, {});
    const SceneInfo info = probe_scene(src);
    std::vector<int> all(info.channels.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    IntegratorSettings s = info.integrator;
    s.rtol = 1e-10;
    s.atol = 1e-14;
    const RunData d = run_case(src, s, all);
    ASSERT_EQ(d.status, CaseStatus::completed) << d.message;
    ResultsWriter::Options wo;
    ResultsWriter w((dir.path() / "ref.h5").string(), info.channels, wo);
    std::vector<double> row(static_cast<std::size_t>(d.y.cols()));
    for (long r = 0; r < d.rows(); ++r) {
      for (long c = 0; c < d.y.cols(); ++c) row[static_cast<std::size_t>(c)] = d.y(r, c);
      w.append(d.time[static_cast<std::size_t>(r)], row);
    }
    w.finish(d.stats, "completed");
  }
  Options of = quiet_options(scene, dir.path() / "b");
  of.reference_file = (dir.path() / "ref.h5").string();
  of.channels = "spring.f*";
  const auto b = work_precision(of, {{"ida rtol=1e-5", ""}});
  ASSERT_EQ(b.cases.size(), 1u);
  EXPECT_EQ(b.cases[0].status, CaseStatus::completed) << b.cases[0].message;
  EXPECT_TRUE(std::isfinite(b.cases[0].error));
  EXPECT_LE(b.cases[0].error, a.cases[0].error * 1.0001);  // fewer channels, same reference
  // a scene with another end time does not fit the file
  of.t_end = 0.03;
  EXPECT_NE(input_error([&] {
              work_precision(of, {{"ida", ""}});
            }).find("no output row"),
            std::string::npos);
}

// --- convergence ---------------------------------------------------------------------

TEST(StudyConvergence, GeneralizedAlphaIsSecondOrderOnAnUndampedOscillator) {
  const auto t0 = std::chrono::steady_clock::now();
  TempDir dir("conv");
  const std::string scene = dir.write("osc.yaml", oscillator_scene(0.1, 1e-3));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-11 atol=1e-15";
  o.channels = "c.p*,spring.f*";
  o.plot = true;
  const auto res =
      convergence(o, {"generalized-alpha rho_inf=1 step_control=fixed rtol=1e-10 atol=1e-14 "
                      "step=4e-5,2e-5,1e-5,5e-6",
                      ""});
  EXPECT_EQ(res.key, "step");
  ASSERT_EQ(res.cases.size(), 4u);
  EXPECT_EQ(res.x.front(), 4e-5);
  for (std::size_t i = 0; i < res.cases.size(); ++i) {
    std::cout << "step " << res.x[i] << ": error " << res.cases[i].error << ", order "
              << res.pair_order[i] << "\n";
    EXPECT_EQ(res.cases[i].status, CaseStatus::completed) << res.cases[i].message;
  }
  std::cout << "observed order " << res.slope << " (omega h = " << oscillator_omega() * 4e-5
            << " .. " << oscillator_omega() * 5e-6 << ")\n";
  EXPECT_EQ(res.points, 4);
  EXPECT_NEAR(res.slope, 2.0, 0.1);
  for (const char* f : {"convergence.csv", "convergence.md"})
    EXPECT_TRUE(fs::exists(dir.path() / "out" / f)) << f;
  // a family must sweep exactly one of step, rtol
  EXPECT_NE(input_error([&] {
              convergence(o, {"generalized-alpha rho_inf=0.5,1", ""});
            }).find("step or rtol"),
            std::string::npos);
  EXPECT_NE(input_error([&] {
              convergence(o, {"generalized-alpha step=1e-5", ""});
            }).find("none is swept"),
            std::string::npos);
  const double s = seconds_since(t0);
  std::cout << "convergence study: " << s << " s\n";
  EXPECT_LT(s, 20.0);
}

// --- stability ------------------------------------------------------------------------

// Newmark beta = 1/6, gamma = 1/2 (linear acceleration) on an undamped mode is
// stable for h omega <= 2 sqrt(3) (Hughes, The Finite Element Method, 1987,
// s. 9.1; Newmark 1959). With Newton iteration the discrete step is the linear
// method itself, so the study must find that limit.
TEST(StudyStability, LinearAccelerationLimitIsTwoRootThreeOverOmega) {
  const auto t0 = std::chrono::steady_clock::now();
  TempDir dir("stab");
  const double w = oscillator_omega(), limit = 2 * std::sqrt(3.0);
  const double h_lim = limit / w;
  // 300 limit steps: growth by 10 within the run for h omega >= 1.0001 limit
  const std::string scene = dir.write("osc.yaml", oscillator_scene(300 * h_lim, h_lim / 8));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-8 atol=1e-12";
  o.channels = "spring.f*";
  o.plot = true;
  StabilityOptions so;
  so.h_min = 0.5 * h_lim;
  so.h_max = 2.0 * h_lim;
  so.bisections = 12;
  // (a step that lands on a zero of the acceleration, h omega = sqrt 3 at h_min,
  // is balanced against |a_n|: no atol needed)
  const auto res =
      stability(o, {"linear-acceleration iteration=newton step_control=fixed", ""}, so);
  ASSERT_EQ(res.points.size(), 1u);
  const auto& p = res.points[0];
  std::cout << "omega = " << w << " rad/s (m = " << oscillator_mass()
            << " kg): " << to_text(p.status) << ", h omega stable " << p.h_stable * w
            << ", unstable " << p.h_unstable * w << " (2 sqrt 3 = " << limit << "), " << p.runs
            << " runs; " << p.message << "\n";
  EXPECT_EQ(p.status, StabilityStatus::bracketed) << to_text(p.status);
  EXPECT_NEAR(p.h_stable * w, limit, 0.03 * limit);
  EXPECT_NEAR(p.h_unstable * w, limit, 0.03 * limit);
  for (const char* f : {"stability.csv", "stability.md"})
    EXPECT_TRUE(fs::exists(dir.path() / "out" / f)) << f;
  const double s = seconds_since(t0);
  std::cout << "stability study: " << s << " s\n";
  EXPECT_LT(s, 20.0);
}

// A trial cut short by --max-wall says nothing of stability: the search ends
// "timed out" with its bracket so far (HMAX unstable here), not "unstable".
// The reference is not limited.
TEST(StudyStability, ATrialPastMaxWallEndsTheSearchAsTimedOut) {
  TempDir dir("stab_wall");
  const double w = oscillator_omega(), h_lim = 2 * std::sqrt(3.0) / w;
  const std::string scene = dir.write("osc.yaml", oscillator_scene(300 * h_lim, h_lim / 8));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-8 atol=1e-12";
  o.channels = "spring.f*";
  o.max_wall = 0.05;
  StabilityOptions so;
  so.h_min = 1e-5 * h_lim;  // 3e7 steps: far more than 0.05 s
  so.h_max = 2.0 * h_lim;
  so.bisections = 4;
  const auto res =
      stability(o, {"linear-acceleration iteration=newton step_control=fixed", ""}, so);
  ASSERT_EQ(res.points.size(), 1u);
  const auto& p = res.points[0];
  EXPECT_EQ(p.status, StabilityStatus::timed_out) << to_text(p.status) << ": " << p.message;
  EXPECT_EQ(p.runs, 2);
  EXPECT_EQ(p.h_unstable, so.h_max);
  EXPECT_TRUE(std::isnan(p.h_stable));
  EXPECT_NE(p.message.find("timed out"), std::string::npos) << p.message;
}

// Generalized-alpha (rho_inf = 0.8) is unconditionally stable. With a step of
// h omega = 48 on a 1 ms output grid the outputs lie inside the steps, and the
// interpolant swings to about ten times the physical amplitude in the first
// step while the solution at the step points stays bounded and decays: the
// study must judge the step points and call it stable (it called it unstable
// at h omega = 48 before).
TEST(StudyStability, LongStepsAreJudgedAtTheStepPointsNotTheInterpolatedOutputs) {
  TempDir dir("stab_long");
  const double w = oscillator_omega();
  const double h_max = 48.0 / w;
  const std::string scene = dir.write("osc.yaml", oscillator_scene(20.0 * h_max, 1e-3));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-7 atol=1e-11";
  o.channels = "c.v*,spring.f*";
  StabilityOptions so;
  so.h_min = 0.01 / w;
  so.h_max = h_max;
  so.bisections = 0;
  const auto res =
      stability(o, {"generalized-alpha rho_inf=0.8 step_control=fixed iteration=newton", ""}, so);
  ASSERT_EQ(res.points.size(), 1u);
  const auto& p = res.points[0];
  std::cout << "omega = " << w << " rad/s, h omega = " << h_max * w << ": " << to_text(p.status)
            << "; " << p.message << "; " << p.interpolation << "\n";
  EXPECT_EQ(p.status, StabilityStatus::stable_to_hmax) << p.message;
}

// A sweep over the spring stiffness: the limit step scales as 1/sqrt(k).
// generalized-alpha with rho_inf = 1 is unconditionally stable: "stable up to HMAX".
TEST(StudyStability, SweepAndUnconditionallyStableCase) {
  TempDir dir("stab_sweep");
  const double w = oscillator_omega(), h_lim = 2 * std::sqrt(3.0) / w;
  const std::string scene = dir.write("osc.yaml", oscillator_scene(100 * h_lim, h_lim / 4));
  Options o = quiet_options(scene, dir.path() / "out");
  o.reference = "ida rtol=1e-7 atol=1e-12";
  o.channels = "spring.f*";
  o.plot = true;
  StabilityOptions so;
  so.h_min = 0.1 * h_lim;
  so.h_max = 4.0 * h_lim;
  so.bisections = 0;
  const auto ga = stability(o, {"generalized-alpha rho_inf=1 step_control=fixed", ""}, so);
  ASSERT_EQ(ga.points.size(), 1u);
  EXPECT_EQ(ga.points[0].status, StabilityStatus::stable_to_hmax)
      << to_text(ga.points[0].status) << ": " << ga.points[0].message;
  EXPECT_EQ(ga.points[0].h_stable, so.h_max);
  EXPECT_NE(input_error([&] {
              stability(o, {"ida", ""}, so);
            }).find("fixed step"),
            std::string::npos);
  so.sweep = "spring.stiffness=[1e4,1e4,1e4],[1e6,1e6,1e6]";
  so.bisections = 4;
  const auto sw = stability(o, {"generalized-alpha rho_inf=1 step_control=fixed", ""}, so);
  ASSERT_EQ(sw.points.size(), 2u);
  EXPECT_EQ(sw.sweep_key, "spring.stiffness");
  EXPECT_EQ(sw.points[1].value, "[1e6,1e6,1e6]");
  for (const auto& p : sw.points)
    EXPECT_EQ(p.status, StabilityStatus::stable_to_hmax) << to_text(p.status) << ": " << p.message;
  EXPECT_TRUE(fs::exists(dir.path() / "out" / "stability.csv"));
}

// probe_scene reads the crank angle of every output time from the crank body's
// LOF alone; the values are those of the run's crank_angle channel, which
// OutputSet::values computes along with every other channel.
TEST(StudyProbe, CrankAnglesAreTheRunsChannel) {
  const std::string path = std::string(EVAS_SOURCE_DIR) + "/validation/engine/engine.yaml";
  const SceneSource src = load_scene_source(path, {});
  const SceneInfo info = probe_scene(src);
  ASSERT_GE(info.crank_channel, 0);
  ASSERT_EQ(info.crank.size(), info.times.size());
  ASSERT_GT(info.times.size(), 1000u);
  Scene scene = src.parse();
  System sys(*scene.model);
  OutputSet out(scene.output, sys, scene.t_start, scene.t_end);
  Vec q0, v0;
  sys.initial_state(q0, v0);
  std::vector<double> row(static_cast<std::size_t>(out.size()));
  for (std::size_t k = 0; k < info.times.size(); k += 97) {
    out.values(info.times[k], q0.data(), v0.data(), row.data());
    EXPECT_EQ(info.crank[k], row[static_cast<std::size_t>(info.crank_channel)]) << "row " << k;
  }
  // the grid is 1 deg of crank angle
  for (std::size_t k = 1; k < info.crank.size(); ++k)
    ASSERT_NEAR(info.crank[k] - info.crank[k - 1], 1.0, 1e-9) << "row " << k;
}
