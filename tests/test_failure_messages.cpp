// A failed IDA run says where: time, state, and the coordinate with the largest
// weighted local error estimate of the last step, named by body and mode.
#include <gtest/gtest.h>

#include "integrators/integrator.h"
#include "io/scene.h"
#include "solver/system.h"

using namespace evas;

TEST(FailureMessages, IdaNamesTheCoordinateWithTheLargestLocalError) {
  Scene scene = read_scene(std::string(EVAS_SOURCE_DIR) + "/scenes/demo.yaml");
  System sys(*scene.model);
  Vec q0, v0;
  sys.initial_state(q0, v0);
  IntegratorSettings s = scene.integrator;
  s.name = "ida";
  s.max_steps = 20;  // too little work allowed: IDA gives up in its first output interval
  auto integ = make_integrator("ida");
  integ->init(sys, scene.t_start, q0, v0, s);
  try {
    integrate(*integ, sys, scene.t_start, {0.05}, [](double, const Vec&, const Vec&) {});
    FAIL() << "20 steps reached t = 0.05 s";
  } catch (const RunError& e) {
    const std::string msg = e.what();
    std::printf("[ message ] %s\n", msg.c_str());
    EXPECT_NE(msg.find("largest local error (weighted "), std::string::npos) << msg;
    EXPECT_NE(msg.find(" of body '"), std::string::npos) << msg;
    EXPECT_NE(msg.find("', mode "), std::string::npos) << msg;
    EXPECT_NE(msg.find("; state: t = "), std::string::npos) << msg;
  }
  EXPECT_EQ(sys.describe_coordinate(0).rfind("body '", 0), 0u);
  EXPECT_EQ(sys.describe_coordinate(sys.size()), "coordinate " + std::to_string(sys.size()));
}
