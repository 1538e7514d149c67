// A Camera in the sim (both engines): announced in SIM_MODEL with its mount
// and parameters, never read (no SIM_SENSOR readings, however many steps),
// and every command to it refused, saying simpartner-camera renders it.
// The same robot without the camera steps to the same state.
#include <gtest/gtest.h>

#include <map>

#include "../support/engines.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeSim;

// The arm robot of test_worlds.h with a Position sensor and a Camera, both
// at 100 Hz.
std::string CameraArmRobot() {
  std::string robot = testing::ArmRobot();
  robot.insert(robot.find("  <actuator"),
               R"(  <sensor type="Position" name="Where"><bodyRef>Base</bodyRef><rate>100</rate></sensor>
  <sensor type="Camera" name="Eye"><bodyRef>Base</bodyRef>)" +
                   testing::Transform(0.1, 0.8, 0) + R"(<rate>100</rate>
    <parameter name="width">320</parameter><parameter name="height">200</parameter>
    <parameter name="fov">1.1</parameter><parameter name="near">0.2</parameter>
    <parameter name="far">40</parameter><parameter name="depth">metres</parameter>
  </sensor>
)");
  return robot;
}

class CameraInTheSim : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<Simulation> Make(const std::string& robot) {
    Parameters params;
    params.engine = GetParam();
    return MakeSim(testing::ArmWorld(), {{"arm.xml", robot}}, params);
  }
};

TEST_P(CameraInTheSim, IsAnnouncedNeverReadAndTakesNoCommand) {
  auto sim = Make(CameraArmRobot());
  model_t m;
  sim->FillModel(&m);
  const sensor_t* eye = nullptr;
  for (const sensor_t& s : m.sensors)
    if (s.name == "Eye") eye = &s;
  ASSERT_NE(eye, nullptr);
  EXPECT_EQ(eye->kind, sensor_t::KIND_CAMERA);
  EXPECT_EQ(eye->kind, 10);  // fixed between the sensor kinds (lcmtypes/sensor_t.lcm)
  EXPECT_DOUBLE_EQ(eye->rate, 100);
  EXPECT_EQ(eye->params, (std::vector<double>{320, 200, 1.1, 0.2, 40, 1}));
  EXPECT_DOUBLE_EQ(eye->position[1], 0.8);
  EXPECT_DOUBLE_EQ(eye->orientation[0], 1);

  int position_readings = 0;
  for (int k = 0; k < 50; ++k) {
    ASSERT_TRUE(sim->Step());
    for (const sensor_reading_t& r : sim->TakeSensorReadings()) {
      EXPECT_NE(r.kind, sensor_t::KIND_CAMERA) << "a camera reading at step " << r.step;
      position_readings += r.name == "Where";
    }
  }
  EXPECT_EQ(position_readings, 5);  // 100 Hz for 50 ms: the sensors still run

  for (int8_t action : {command_t::ACTION_READ, command_t::ACTION_SET,
                        command_t::ACTION_SENSOR_PARAMS}) {
    const auto reply = sim->Submit(Command("Eye", action, {10}));
    ASSERT_TRUE(reply.has_value()) << "action " << int(action) << " was queued";
    EXPECT_FALSE(reply->accepted);
    EXPECT_NE(reply->reason.find("sensor 'Eye' (Camera): simpartner-camera renders it"),
              std::string::npos)
        << reply->reason;
  }
}

TEST_P(CameraInTheSim, ChangesNoPhysics) {
  auto with = Make(CameraArmRobot());
  auto without = Make(testing::ArmRobot());
  for (int k = 0; k < 200; ++k) {
    ASSERT_TRUE(with->Step());
    ASSERT_TRUE(without->Step());
  }
  state_t a, b;
  with->FillState(&a);
  without->FillState(&b);
  ASSERT_EQ(a.num_bodies, b.num_bodies);
  for (size_t i = 0; i < a.bodies.size(); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(a.bodies[i].position[k], b.bodies[i].position[k]);
}

INSTANTIATE_TEST_SUITE_P(Engines, CameraInTheSim, test_support::AllEngines(),
                         test_support::EngineTestName);

}  // namespace
}  // namespace simpartner::sim
