// The element parameter reference in docs/elements.md is the registry's own
// output: one declaration feeds the scene reader, validation and the docs.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <sstream>

#include "elements/registry.h"
#include "integrators/settings.h"

TEST(Docs, ElementReferenceMatchesDeclarations) {
  std::ifstream f(std::string(EVAS_SOURCE_DIR) + "/docs/elements.md");
  ASSERT_TRUE(f) << "docs/elements.md missing";
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  const std::string begin = "<!-- BEGIN GENERATED: evas elements -->\n";
  const std::string end = "<!-- END GENERATED -->";
  const auto a = doc.find(begin), b = doc.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  auto trim = [](std::string s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
  };
  const std::string generated = doc.substr(a + begin.size(), b - a - begin.size());
  EXPECT_EQ(trim(generated), trim(evas::element_reference_markdown()))
      << "docs/elements.md is out of date: run `make docs`";
}

// The integrator settings table in docs/user-guide.md is the declaration's own
// output (integrators/settings.cpp).
TEST(Docs, IntegratorSettingsMatchDeclarations) {
  std::ifstream f(std::string(EVAS_SOURCE_DIR) + "/docs/user-guide.md");
  ASSERT_TRUE(f) << "docs/user-guide.md missing";
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  const std::string begin = "<!-- BEGIN GENERATED: evas run --help-settings -->\n";
  const auto a = doc.find(begin), b = doc.find("<!-- END GENERATED -->", a);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  EXPECT_EQ(doc.substr(a + begin.size(), b - a - begin.size()), evas::settings_reference())
      << "docs/user-guide.md is out of date: run `make docs`";
}
