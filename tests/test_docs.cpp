// The element parameter reference in docs/elements.md is the registry's own
// output: one declaration feeds the scene reader, validation and the docs.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <sstream>

#include "elements/registry.h"
#include "integrators/integrator.h"
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

namespace {

std::string doc_text(const std::string& rel) {
  std::ifstream f(std::string(EVAS_SOURCE_DIR) + "/" + rel);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace

// docs/study.md lists every case key (an integrator setting) by name, and the
// user guide's --integrator and the README's table name every built-in
// integrator: a setting or an integrator added later fails here until the
// docs name it.
TEST(Docs, CaseKeysAndIntegratorListsAreComplete) {
  const std::string study = doc_text("docs/study.md"), guide = doc_text("docs/user-guide.md"),
                    readme = doc_text("README.md");
  std::istringstream table(evas::settings_reference());
  for (std::string line; std::getline(table, line);) {
    if (line.rfind("| `", 0) != 0) continue;
    const std::string key = line.substr(3, line.find('`', 3) - 3);
    if (key == "name") continue;  // the integrator itself, not a key
    EXPECT_NE(study.find("`" + key + "`"), std::string::npos)
        << "docs/study.md does not list the case key '" << key << "'";
  }
  const auto flag = guide.find("| `--integrator NAME` |");
  ASSERT_NE(flag, std::string::npos);
  const std::string row = guide.substr(flag, guide.find('\n', flag) - flag);
  for (const std::string& name : evas::builtin_integrator_names()) {
    EXPECT_NE(row.find("`" + name + "`"), std::string::npos)
        << "docs/user-guide.md --integrator lacks " << name;
    EXPECT_NE(readme.find("| `" + name + "` |"), std::string::npos)
        << "README.md's integrator table lacks " << name;
  }
  for (const char* stale : {"all four integrators", "build-radau/libevas_radau.so --integrator"})
    for (const auto& [file, text] :
         {std::pair<const char*, const std::string*>{"README.md", &readme},
          {"docs/user-guide.md", &guide}})
      EXPECT_EQ(text->find(stale), std::string::npos) << file << " says '" << stale << "'";
}
