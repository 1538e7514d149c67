// The HUD's first line without a display: the world, the robot and the
// physics engine the model names, then time, speed and run state.
#include <gtest/gtest.h>

#include "simpartner/viewer/hud_text.h"

namespace simpartner::viewer {
namespace {

model_t GenThreeModel(const std::string& engine) {
  model_t m{};
  m.world_name = "FlatGround";
  m.engine = engine;
  m.num_robots = 1;
  m.robots.resize(1);
  m.robots[0].model = "WorkPartner gen3";
  return m;
}

TEST(HudText, TheSimLineNamesTheEngineOfTheModel) {
  status_t status{};
  status.engine = "mujoco";
  status.run_state = status_t::RUN_PAUSED;
  status.sim_time = 2.5;
  status.step = 2500;
  status.real_time_factor = 31.25;
  EXPECT_EQ(SimLine(GenThreeModel("mujoco"), nullptr, &status),
            "FlatGround / WorkPartner gen3   engine mujoco   t 2.500 s   step 2500   x31.25 real "
            "time   PAUSED");
  state_t state{};
  state.sim_time = 0.004;
  state.step = 4;
  EXPECT_EQ(SimLine(GenThreeModel("ode"), &state, nullptr),
            "FlatGround / WorkPartner gen3   engine ode   t 0.004 s   step 4");
}

// A model without an engine comes from a sim older than the field: ODE,
// the only engine there was.
TEST(HudText, AModelWithoutAnEngineIsShownAsOde) {
  EXPECT_EQ(SimLine(GenThreeModel(""), nullptr, nullptr),
            "FlatGround / WorkPartner gen3   engine ode   no state yet");
}

}  // namespace
}  // namespace simpartner::viewer
