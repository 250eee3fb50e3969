// Element parameters declared once (elements/param_binding.h): the table's
// defaults are the parameter struct's member initialisers, and reading a scene
// that gives only the required parameters yields a default struct with those
// filled in. Checked for both elements whose parameters are a struct.
#include <gtest/gtest.h>

#include "elements/journal_bearing.h"
#include "elements/param_binding.h"
#include "elements/piston_conrod.h"
#include "elements/registry.h"

namespace {

using namespace evas;

// The values of the required parameters only; complete_params fills the rest.
ParamValues required_only(const ElementType& t, double value) {
  ParamValues v;
  for (const auto& p : t.params)
    if (p.required) v.numbers[p.key] = {value};
  complete_params(t, v, "test");
  return v;
}

TEST(ParamBinding, JournalBearingDefaultsAreTheStructs) {
  const ElementType& t = element_type("journal-bearing");
  ParamValues v = required_only(t, 0.02);
  const auto e = t.make("jb", {0, 1}, v);
  const auto& p = dynamic_cast<const JournalBearing&>(*e).params();
  const JournalBearingParams d{};
  EXPECT_EQ(p.radius, 0.02);
  EXPECT_EQ(p.width, 0.02);
  EXPECT_EQ(p.clearance, 0.02);
  EXPECT_EQ(p.viscosity, 0.02);
  EXPECT_EQ(p.closed_form, d.closed_form);
  EXPECT_EQ(p.n_delta, d.n_delta);
  EXPECT_EQ(p.halves, d.halves);
  EXPECT_EQ(p.eps_max, d.eps_max);
  EXPECT_EQ(p.contact_stiffness, d.contact_stiffness);
  EXPECT_EQ(p.contact_exponent, d.contact_exponent);
  EXPECT_EQ(p.journal_speed, d.journal_speed);
  // The documented defaults are the same numbers.
  for (const auto& s : t.params) {
    if (s.key == "eps_max") {
      EXPECT_EQ(s.default_value.at(0), d.eps_max);
    }
  }
}

TEST(ParamBinding, PistonDefaultsAreTheStructs) {
  const ElementType& t = element_type("piston-conrod");
  ParamValues v = required_only(t, 0.1);
  v.numbers["conrod_length"] = {0.3};
  v.numbers["speed"] = {100.0};
  v.defaulted.erase("speed");
  const auto e = t.make("pc", {0, 1, 2}, v);
  const auto& p = dynamic_cast<const PistonConrod&>(*e).params();
  const PistonConrodParams d{};
  EXPECT_EQ(p.crank_radius, 0.1);
  EXPECT_EQ(p.conrod_length, 0.3);
  EXPECT_EQ(p.speed, 100.0);
  EXPECT_EQ(p.rec_mass, d.rec_mass);
  EXPECT_EQ(p.cylinder_axis, d.cylinder_axis);
  EXPECT_EQ(p.crank_axis, d.crank_axis);
  EXPECT_EQ(p.friction_velocity, d.friction_velocity);
  EXPECT_EQ(p.liner_height, d.liner_height);
  EXPECT_EQ(p.coupled, d.coupled);
  EXPECT_EQ(p.eq2_side_force, d.eq2_side_force);
}

struct Demo {
  double a = 1.5;
  int n = 3;
  bool on = true;
  Vec3 axis = Vec3(0, 0, 1);
};

TEST(ParamBinding, TableFromTheStruct) {
  const auto b = ParamBinding<Demo>()
                     .number(&Demo::a, "a", "m", "a length", 0.0)
                     .whole(&Demo::n, "n", "-", "a count", 1, 10)
                     .flag(&Demo::on, "mode", "off or on", {"off", "on"}, "on")
                     .vec3(&Demo::axis, "axis", "-", "an axis");
  ASSERT_EQ(b.specs().size(), 4u);
  EXPECT_EQ(b.specs()[0].default_value, std::vector<double>{1.5});
  EXPECT_EQ(b.specs()[1].default_value, std::vector<double>{3.0});
  EXPECT_EQ(b.specs()[2].default_text, "on");
  EXPECT_EQ(b.specs()[3].default_value, (std::vector<double>{0, 0, 1}));

  ParamValues v;
  v.numbers = {{"a", {2.0}}, {"n", {4.0}}, {"axis", {1, 0, 0}}};
  v.texts = {{"mode", "off"}};
  const Demo d = b.read(v, "element 'x'");
  EXPECT_EQ(d.a, 2.0);
  EXPECT_EQ(d.n, 4);
  EXPECT_FALSE(d.on);
  EXPECT_EQ(d.axis, Vec3(1, 0, 0));

  v.numbers["n"] = {2.5};
  try {
    b.read(v, "element 'x'");
    FAIL() << "a fraction was accepted as a whole number";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("element 'x': parameter 'n' = 2.5 must be an integer"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
