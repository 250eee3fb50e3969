// Plausible ranges (elements/plausibility.h): the table names real parameters
// in their declared units; the repository's own engine and demo scenes draw no
// warning; each unit slip the issue lists is named with its conversion, worked
// out here by hand (1 mm = 1e-3 m, 1 um = 1e-6 m, 1 rpm = 2 pi / 60 rad/s,
// 1 bar = 1e5 Pa, 1 cP = 1 mPa s = 1e-3 Pa s, 1 N/mm = 1e3 N/m).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "elements/plausibility.h"
#include "elements/registry.h"
#include "integrators/settings.h"
#include "io/scene.h"
#include "run/step_advice.h"

using namespace evas;

namespace {

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::string warn(const std::string& type, const std::string& key, double x) {
  const PlausibleRange* r = plausible_range(type, key);
  EXPECT_NE(r, nullptr) << type << "." << key;
  return r ? plausibility_warning(*r, x) : "";
}

}  // namespace

TEST(Plausibility, TableNamesDeclaredParametersInTheirUnits) {
  const std::map<Quantity, std::string> unit = {
      {Quantity::Length, "m"},       {Quantity::Speed, "rad/s"}, {Quantity::Pressure, "Pa"},
      {Quantity::Viscosity, "Pa s"}, {Quantity::Mass, "kg"},     {Quantity::Stiffness, "N/m"},
      {Quantity::Damping, "N s/m"},  {Quantity::Force, "N"}};
  for (const PlausibleRange& r : plausible_ranges()) {
    SCOPED_TRACE(r.type + "." + r.key);
    EXPECT_GT(r.hi, r.lo);
    EXPECT_GE(r.lo, 0.0);
    if (r.type == "lof" || r.type == "generate") continue;  // scene keys, not element parameters
    const ElementType& t = element_type(r.type);
    const ParamSpec* spec = nullptr;
    for (const auto& p : t.params)
      if (p.key == r.key) spec = &p;
    ASSERT_NE(spec, nullptr);
    // the declared unit starts with the SI unit of the quantity (polynomial
    // stiffnesses list N/m, N/m^2, ...)
    EXPECT_EQ(spec->unit.rfind(unit.at(r.quantity), 0), 0u) << spec->unit;
    // a plausible value is a valid one
    const double mid = std::sqrt(std::max(r.lo, 1e-300) * r.hi);
    EXPECT_GE(mid, spec->min);
    EXPECT_LE(mid, spec->max);
  }
}

TEST(Plausibility, RepositoryScenesDrawNoWarning) {
  for (const char* rel :
       {"/validation/engine/engine.yaml", "/scenes/demo.yaml", "/scenes/hinged_beam.yaml"}) {
    const Scene s = read_scene(std::string(EVAS_SOURCE_DIR) + rel);
    EXPECT_TRUE(s.warnings.empty()) << rel << ": " << (s.warnings.empty() ? "" : s.warnings[0]);
  }
}

TEST(Plausibility, UnitSlipsAreNamedWithTheirConversion) {
  // in range: nothing
  EXPECT_EQ(warn("journal-bearing", "clearance", 4e-5), "");
  EXPECT_EQ(warn("lof", "speed", 314.159), "");
  EXPECT_EQ(warn("lof", "speed", -314.159), "");  // turning backwards is a magnitude
  EXPECT_EQ(warn("piston-conrod", "crankcase_pressure", 0.0), "");  // gauge pressures: 0

  // micrometres typed for metres: 40 um = 4e-5 m (not 40 mm = 0.04 m, out of range)
  EXPECT_TRUE(contains(warn("journal-bearing", "clearance", 40), "(40 um would be 4e-05 m)"));
  // millimetres: 0.04 mm = 4e-5 m
  EXPECT_TRUE(contains(warn("journal-bearing", "clearance", 0.04), "(0.04 mm would be 4e-05 m)"));
  EXPECT_TRUE(contains(warn("piston-conrod", "bore", 86), "(86 mm would be 0.086 m)"));
  // rpm: 3000 rpm = 3000 * 2 pi / 60 = 314.159 rad/s
  EXPECT_TRUE(contains(warn("lof", "speed", 3000), "(3000 rpm would be 314.159 rad/s)"));
  EXPECT_TRUE(contains(warn("motor", "speed", -6000), "(-6000 rpm would be -628.319 rad/s)"));
  // bar: 1 bar = 1e5 Pa
  EXPECT_TRUE(
      contains(warn("piston-conrod", "crankcase_pressure", 1), "(1 bar would be 100000 Pa)"));
  // centipoise: 15 cP = 0.015 Pa s
  EXPECT_TRUE(
      contains(warn("journal-bearing", "viscosity", 15), "(15 mPa s (cP) would be 0.015 Pa s)"));
  // N/mm: 150 N/mm = 1.5e5 N/m
  EXPECT_TRUE(contains(warn("engine-mount", "k_x", 150), "(150 N/mm would be 150000 N/m)"));
  // grams: 450 g = 0.45 kg needs the bore (below); a piston of 50 t is out of range itself
  EXPECT_TRUE(contains(warn("piston-conrod", "piston_mass", 5e4), "(50000 g would be 50 kg)"));
  // a generated body: MPa for Pa, g/cm^3 for kg/m^3, mm^2 for m^2
  EXPECT_TRUE(
      contains(warn("generate", "youngs", 210000), "(210000 MPa (N/mm^2) would be 2.1e+11 Pa)"));
  EXPECT_TRUE(contains(warn("generate", "density", 7.85), "(7.85 g/cm^3 would be 7850 kg/m^3)"));
  EXPECT_TRUE(contains(warn("generate", "area", 20), "(20 mm^2 would be 2e-05 m^2)"));
  // a pressure table in bar: peak 80 -> 8e6 Pa
  EXPECT_TRUE(contains(peak_pressure_warning(80, "table 'p.txt'"),
                       "the cylinder pressure table 'p.txt' peaks at 80 Pa"));
  EXPECT_TRUE(contains(peak_pressure_warning(80, "t"), "(a table in bar would peak at 8e+06 Pa)"));
  EXPECT_EQ(peak_pressure_warning(1.4e7, "t"), "");
  // nothing explains it
  EXPECT_TRUE(contains(warn("journal-bearing", "clearance", 1e6), "no common unit slip"));
}

TEST(Plausibility, CrossChecksOfAnElement) {
  auto values = [](const std::string& type, std::map<std::string, double> given) {
    ParamValues v;
    for (const auto& [k, x] : given) v.numbers[k] = {x};
    complete_params(element_type(type), v, "t");
    return v;
  };
  std::vector<std::string> w;
  // a clearance as large as the radius cannot be run: an error naming the slip
  try {
    check_plausible(
        element_type("journal-bearing"),
        values("journal-bearing",
               {{"radius", 0.03}, {"width", 0.02}, {"clearance", 40}, {"viscosity", 0.01}}),
        "main1", w);
    ADD_FAILURE() << "a clearance of 40 m in a 0.03 m journal was accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(),
                         "main1: clearance 40 m is not smaller than the journal radius "
                         "0.03 m"))
        << e.what();
    EXPECT_TRUE(contains(e.what(), "(40 um is 4e-05 m)")) << e.what();
  }
  // a clearance of 1 % of the radius: c/R ten times the usual
  w.clear();
  check_plausible(
      element_type("journal-bearing"),
      values("journal-bearing",
             {{"radius", 0.03}, {"width", 0.02}, {"clearance", 3e-4}, {"viscosity", 0.01}}),
      "main1", w);
  EXPECT_TRUE(w.empty()) << w[0];  // 1 % is below the 2 % limit
  check_plausible(
      element_type("journal-bearing"),
      values("journal-bearing",
             {{"radius", 0.01}, {"width", 0.02}, {"clearance", 4e-4}, {"viscosity", 0.01}}),
      "main1", w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(contains(w[0], "clearance 0.0004 m is 4 % of the journal radius 0.01 m")) << w[0];
  // a piston of 450 (grams) at an 86-mm bore: 450 / 0.086^3 = 7.07e5 kg/m^3,
  // 0.45 kg gives 707 kg/m^3, inside 100 .. 2e4
  w.clear();
  check_plausible(element_type("piston-conrod"),
                  values("piston-conrod", {{"crank_radius", 0.043},
                                           {"conrod_length", 0.14},
                                           {"bore", 0.086},
                                           {"piston_mass", 450}}),
                  "cyl1", w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_TRUE(contains(w[0], "piston_mass 450 kg for a bore of 0.086 m")) << w[0];
  EXPECT_TRUE(contains(w[0], "(450 g would be 0.45 kg)")) << w[0];
}

TEST(Plausibility, StepsFarTooSmallAreSaidBeforeTheRun) {
  IntegratorSettings s;
  set_integrator_setting(s, "name", "generalized-alpha");
  set_integrator_setting(s, "step", "1e-12");
  // 0.2 s / 1e-12 s = 2e11 steps
  const std::string w = step_count_warning(s, 0.0, 0.2);
  EXPECT_TRUE(contains(w, "step 1e-12 s needs about 2e+11 steps to reach t = 0.2 s")) << w;
  set_integrator_setting(s, "step", "1e-5");  // 2e4 steps: nothing to say
  EXPECT_EQ(step_count_warning(s, 0.0, 0.2), "");
  set_integrator_setting(s, "name", "ida");  // adaptive: the step is not fixed
  set_integrator_setting(s, "step", "1e-12");
  EXPECT_EQ(step_count_warning(s, 0.0, 0.2), "");
}

TEST(Plausibility, MeshUnitsOffByThousandsAreNamed) {
  const std::vector<MeshUnits> systems = {
      {"SI", 1.0, 1.0}, {"mm-t-s", 1e-3, 1e3}, {"mm-kg-s", 1e-3, 1.0}};
  // a steel block 0.2 x 0.1 x 0.08 m, filling half its box: 0.5 * 1.6e-3 m^3 * 7850 = 6.28 kg
  const Vec3 box(0.2, 0.1, 0.08);
  EXPECT_EQ(mesh_units_warning(6.28, box, systems[1], systems), "");
  // the same mm mesh read as SI: 1000 x larger, 1e-3 x the mass (t read as kg)
  const std::string w = mesh_units_warning(6.28e-3, box * 1e3, systems[0], systems);
  EXPECT_TRUE(contains(w,
                       "read as SI, the body has a mass of 0.00628 kg and a bounding box of "
                       "200 x 100 x 80 m"))
      << w;
  EXPECT_TRUE(contains(w,
                       "the files are likely in mm-t-s (then a 6.28 kg part of 0.2 x 0.1 x "
                       "0.08 m)"))
      << w;
}
