// The demo scene (scenes/demo.yaml) with another end time and its output block
// replaced, for tests of output channels.
#pragma once

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "integrators/integrator.h"
#include "integrators/settings.h"
#include "io/scene.h"
#include "run/run.h"
#include "run/sink.h"

namespace evas::test_scenes {

inline const std::string kDemo = std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml";

/// The demo scene's text ending at `t_end` [s] with `output` (a YAML block
/// starting "output:") in place of its own.
inline std::string demo_with_output(const std::string& output, const std::string& t_end) {
  std::ifstream f(kDemo);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string text = ss.str();
  const std::string span = "time: {start: 0, end: 0.15}";
  const auto tpos = text.find(span);
  EXPECT_NE(tpos, std::string::npos);
  if (tpos != std::string::npos)
    text.replace(tpos, span.size(), "time: {start: 0, end: " + t_end + "}");
  const auto at = text.find("\noutput:");
  EXPECT_NE(at, std::string::npos);
  const auto end = text.find("\n\n", at + 1);
  return text.substr(0, at + 1) + output + (end == std::string::npos ? "" : text.substr(end));
}

/// Runs `scene` with IDA at rtol 1e-11, atol 1e-14 into `sink`; the outcome.
inline run::Outcome run_tight(const Scene& scene, run::MemorySink& sink) {
  IntegratorSettings s = scene.integrator;
  set_integrator_setting(s, "name", "ida");
  set_integrator_setting(s, "rtol", "1e-11");
  set_integrator_setting(s, "atol", "1e-14");
  const std::unique_ptr<Integrator> integ = make_integrator(s.name);
  run::SceneRun sr(scene, scene.t_end);
  return sr.perform(*integ, s, sink);
}

}  // namespace evas::test_scenes
