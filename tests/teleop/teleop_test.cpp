// Teleop's logic without a bus: mapping files and their errors, plans
// against the shipped worlds' robots (wheel signs from the joint axes),
// the safety rules and the pacing of command batches.
#include <SDL2/SDL_gamecontroller.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "simpartner/actuator_t.hpp"
#include "simpartner/teleop/mapping.h"
#include "simpartner/teleop/teleop.h"

namespace simpartner::teleop {
namespace {

const std::string kMappings = std::string(SP_SOURCE_DIR) + "/teleop/mappings";
std::string World(const std::string& name) {
  return std::string(SP_SOURCE_DIR) + "/models/worlds/" + name;
}

// A minimal mapping for gen1; tests replace lines of it.
const std::string kGen1 =
    "model WorkPartner gen1\n"
    "forward RearChassis +x\n"
    "deadman rightshoulder\n"
    "drive lefty -2\n"
    "wheel Axle1Motor\n"
    "wheel Axle2Motor\n"
    "wheel Axle3Motor\n"
    "wheel Axle4Motor 500\n"
    "steer leftx TurnerMotor -0.5 1000 100 100 0\n"
    "level body dpup dpdown 0.1 -0.2 0.3 1000 10 0 0\n"
    "joint body Hip1Motor 1\n"
    "joint body Knee1Motor -2\n";

std::string ErrorOf(const std::string& text, const model_t* model = nullptr) {
  try {
    const Mapping m = ParseMapping(text, "m.map");
    if (model) BuildPlan(m, *model);
  } catch (const MappingError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(MappingTest, ParsesEveryStatement) {
  const Mapping m = ParseMapping(kGen1, "m.map");
  EXPECT_EQ(m.model, "WorkPartner gen1");
  EXPECT_EQ(m.forward_body, "RearChassis");
  EXPECT_EQ(m.deadman_button, SDL_CONTROLLER_BUTTON_RIGHTSHOULDER);
  EXPECT_EQ(m.drive_axis, SDL_CONTROLLER_AXIS_LEFTY);
  EXPECT_EQ(m.drive_scale, -2);
  ASSERT_EQ(m.wheels.size(), 4u);
  EXPECT_EQ(m.wheels[3].max_force, 500);
  ASSERT_TRUE(m.steer);
  EXPECT_EQ(m.steer->gains.i, 100);
  ASSERT_EQ(m.levels.size(), 1u);
  EXPECT_EQ(m.levels[0].button_minus, SDL_CONTROLLER_BUTTON_DPAD_DOWN);
  ASSERT_EQ(m.joints.size(), 2u);
  EXPECT_EQ(m.joints[1].factor, -2);
}

TEST(MappingTest, ErrorsNameFileLineAndValue) {
  EXPECT_NE(ErrorOf(Replace(kGen1, "deadman rightshoulder", "deadman rightshoulda"))
                .find("m.map:3: button 'rightshoulda' is not an SDL game controller button"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "drive lefty", "drive leftz"))
                .find("m.map:4: axis 'leftz' is not an SDL game controller axis"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "drive lefty -2", "drive lefty fast"))
                .find("m.map:4: drive scale: 'fast' is not a finite number"),
            std::string::npos);
  EXPECT_NE(ErrorOf(kGen1 + "jump a 3\n").find("m.map:13: unknown statement 'jump'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(kGen1 + "joint legs Hip2Motor 1\n")
                .find("m.map:13: level 'legs' is not defined above"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "deadman rightshoulder\n", ""))
                .find("m.map:0: no 'deadman <button>'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "forward RearChassis +x", "forward RearChassis x"))
                .find("m.map:2: forward direction 'x' must be one of"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "-0.2 0.3", "0.2 0.3")).find("m.map:10: level 'body': need min"),
            std::string::npos);
  // A wrong name is not also reported as missing.
  EXPECT_EQ(ErrorOf(Replace(kGen1, "deadman rightshoulder", "deadman rightshoulda")).find("no 'deadman"),
            std::string::npos);
  // Several problems: all of them, in line order.
  const std::string two =
      ErrorOf(Replace(Replace(kGen1, "lefty -2", "lefty x"), "wheel Axle4Motor 500",
                      "wheel Axle4Motor -5"));
  EXPECT_NE(two.find("m.map:4:"), std::string::npos) << two;
  EXPECT_NE(two.find("m.map:8: max force must be > 0"), std::string::npos) << two;
}

TEST(MappingTest, ShippedFileChosenFromTheModelName) {
  EXPECT_EQ(MappingFileFor("WorkPartner gen3", "/d"), "/d/workpartner_gen3.map");
  EXPECT_EQ(MappingFileFor("WorkPartner gen1 light", "/d"), "/d/workpartner_gen1_light.map");
}

TEST(PlanTest, ActuatorsTheModelLacksOrOfTheWrongKind) {
  const model_t gen1 = ModelFromWorldFile(World("gen1_flat.xml"));
  EXPECT_NE(ErrorOf(Replace(kGen1, "wheel Axle2Motor", "wheel Axle5Motor"), &gen1)
                .find("m.map:6: robot 'WorkPartner' (WorkPartner gen1) has no actuator "
                      "'Axle5Motor' (did you mean"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "wheel Axle2Motor", "wheel TurnerMotor"), &gen1)
                .find("m.map:6: 'TurnerMotor' is a angle controller, not a velocity controller"),
            std::string::npos)
      << ErrorOf(Replace(kGen1, "wheel Axle2Motor", "wheel TurnerMotor"), &gen1);
  EXPECT_NE(ErrorOf(kGen1 + "level torso dpleft dpright 0.2 -1 1 1000 10 0 0\n"
                            "joint torso TorsoTurnMotor 1\n",
                    &gen1)
                .find("m.map:14: robot 'WorkPartner' (WorkPartner gen1) has no actuator "
                      "'TorsoTurnMotor'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "forward RearChassis", "forward Chassis"), &gen1)
                .find("m.map:2: robot 'WorkPartner' has no body 'Chassis'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kGen1, "model WorkPartner gen1", "model WorkPartner gen3"), &gen1)
                .find("m.map:1: the mapping is for model 'WorkPartner gen3'; the sim's robots are "
                      "'WorkPartner gen1'"),
            std::string::npos);
}

// The robot file says: axle axis +z on all four wheels, calf body1, wheel
// body2, "a positive velocity rolls the robot forward (+x) on every wheel".
TEST(PlanTest, WheelSignsFollowTheAxesAndTheForwardDirection) {
  const model_t gen1 = ModelFromWorldFile(World("gen1_flat.xml"));
  const Plan plan = BuildPlan(ParseMapping(kGen1, "m.map"), gen1);
  ASSERT_EQ(plan.wheels.size(), 4u);
  for (const Plan::Wheel& w : plan.wheels) EXPECT_EQ(w.sign, 1) << w.target.name;
  // Driving towards the robot's back: every sign flips.
  const Plan back =
      BuildPlan(ParseMapping(Replace(kGen1, "RearChassis +x", "RearChassis -x"), "m.map"), gen1);
  for (const Plan::Wheel& w : back.wheels) EXPECT_EQ(w.sign, -1) << w.target.name;
  // An axle reversed in the model (axis -z) needs the other sign.
  model_t flipped = gen1;
  const int axle2 = plan.wheels[1].target.joint_index;
  for (double& c : flipped.joints[static_cast<size_t>(axle2)].axis[0]) c = -c;
  const Plan mixed = BuildPlan(ParseMapping(kGen1, "m.map"), flipped);
  EXPECT_EQ(mixed.wheels[0].sign, 1);
  EXPECT_EQ(mixed.wheels[1].sign, -1);
  // A "wheel" whose axis points forward cannot drive.
  model_t sideways = gen1;
  double* axis = sideways.joints[static_cast<size_t>(axle2)].axis[0];
  axis[0] = 1, axis[1] = 0, axis[2] = 0;
  EXPECT_NE(ErrorOf(kGen1, &sideways).find("m.map:6: 'Axle2Motor' turns joint 'Axle2' whose axis "
                                           "does not roll the robot along its forward direction"),
            std::string::npos);
}

TEST(PlanTest, EveryShippedMappingFitsItsGeneration) {
  const std::pair<const char*, size_t> worlds[] = {{"gen1_flat.xml", 1},
                                                   {"flat_ground_gen2.xml", 2},
                                                   {"flat_ground.xml", 3},
                                                   {"gen4_flat.xml", 3},
                                                   {"slippery_ground.xml", 1}};
  for (const auto& [world, levels] : worlds) {
    const model_t model = ModelFromWorldFile(World(world));
    const std::string file = MappingFileFor(model.robots[0].model, kMappings);
    try {
      const Plan plan = BuildPlan(LoadMapping(file), model);
      EXPECT_EQ(plan.wheels.size(), 4u) << world;
      for (const Plan::Wheel& w : plan.wheels) EXPECT_EQ(w.sign, 1) << world << " " << w.target.name;
      EXPECT_TRUE(plan.steer) << world;
      EXPECT_EQ(plan.levels.size(), levels) << world;
    } catch (const MappingError& e) {
      ADD_FAILURE() << world << ": " << e.what();
    }
  }
}

class ControllerTest : public ::testing::Test {
 protected:
  ControllerTest()
      : plan_(BuildPlan(ParseMapping(kGen1, "m.map"),
                        ModelFromWorldFile(World("gen1_flat.xml")))) {}
  InputState Pad(double lefty, double leftx, bool deadman) {
    InputState in;
    in.connected = true;
    in.axis[SDL_CONTROLLER_AXIS_LEFTY] = lefty;
    in.axis[SDL_CONTROLLER_AXIS_LEFTX] = leftx;
    in.button[SDL_CONTROLLER_BUTTON_RIGHTSHOULDER] = deadman;
    return in;
  }
  Plan plan_;
};

TEST_F(ControllerTest, WheelsTurnOnlyWithTheDeadmanHeld) {
  Controller c(plan_);
  Demand d = c.Update(Pad(-1, 0, false), StopReason::kNone);
  EXPECT_EQ(d.stop, StopReason::kDeadman);
  d = c.Update(Pad(-1, 0, true), StopReason::kNone);
  ASSERT_TRUE(d.moving());
  EXPECT_DOUBLE_EQ(d.wheel_speed, 2.0);  // stick fully up, drive scale -2
  // Half deflection past the 0.1 dead zone: (0.55 - 0.1) / 0.9 = 0.5.
  d = c.Update(Pad(0.55, -0.55, true), StopReason::kNone);
  EXPECT_NEAR(d.wheel_speed, -1.0, 1e-12);
  EXPECT_NEAR(d.steer_angle, 0.25, 1e-12);  // stick left: scale -0.5 * -0.5
  d = c.Update(Pad(0.05, 0.09, true), StopReason::kNone);
  EXPECT_EQ(d.wheel_speed, 0.0);
  EXPECT_EQ(d.steer_angle, 0.0);
  // Outside stops win over a held dead-man.
  for (StopReason r : {StopReason::kSignal, StopReason::kSimSilent}) {
    d = c.Update(Pad(-1, 0, true), r);
    EXPECT_EQ(d.stop, r);
    EXPECT_EQ(d.wheel_speed, 0.0);
  }
  InputState unplugged = Pad(-1, 0, true);
  unplugged.connected = false;
  EXPECT_EQ(c.Update(unplugged, StopReason::kNone).stop, StopReason::kNoController);
}

TEST_F(ControllerTest, StoppedMeansZeroWheelsAndHeldJoints) {
  Controller c(plan_);
  const Demand stop = c.Update(Pad(-1, 1, false), StopReason::kNone);
  const std::vector<command_t> commands = CommandsFor(plan_, stop, true, true);
  // 4 wheels at 0, then HOLD on the Turner, Hip1, Knee1.
  ASSERT_EQ(commands.size(), 7u);
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(commands[k].action, command_t::ACTION_SET);
    // The short form fmax, velocity: the velocity is 0.
    ASSERT_EQ(commands[k].values.size(), 2u) << commands[k].target;
    EXPECT_EQ(commands[k].values[1], 0.0);
  }
  EXPECT_EQ(commands[3].values[0], 500);  // the wheel's own force limit
  for (size_t k = 4; k < 7; ++k) EXPECT_EQ(commands[k].action, command_t::ACTION_HOLD);
  EXPECT_EQ(commands[4].target, "TurnerMotor");
  // Repeats of the stop carry the wheels only.
  EXPECT_EQ(CommandsFor(plan_, stop, true, false).size(), 4u);
}

TEST_F(ControllerTest, MovingCommandsCarrySignedSpeedsAndAngles) {
  Controller c(plan_);
  const Demand d = c.Update(Pad(-1, 1, true), StopReason::kNone);
  const std::vector<command_t> commands = CommandsFor(plan_, d, true, true);
  ASSERT_EQ(commands.size(), 7u);
  EXPECT_EQ(commands[0].values[1], 2.0);
  EXPECT_EQ(commands[4].target, "TurnerMotor");
  // fmax, angle, P, I, D
  ASSERT_EQ(commands[4].values.size(), 5u);
  EXPECT_DOUBLE_EQ(commands[4].values[1], -0.5);
  EXPECT_EQ(commands[4].values[3], 100);
  EXPECT_EQ(CommandsFor(plan_, d, false, true).size(), 5u);  // without the level joints
}

TEST_F(ControllerTest, LevelButtonsStepOnPressWithinTheRange) {
  Controller c(plan_);
  InputState in = Pad(0, 0, true);
  auto press = [&](SDL_GameControllerButton b, bool deadman = true) {
    in.button[SDL_CONTROLLER_BUTTON_RIGHTSHOULDER] = deadman;
    in.button[b] = true;
    c.Update(in, StopReason::kNone);
    c.Update(in, StopReason::kNone);  // still held: no second step
    in.button[b] = false;
    return c.Update(in, StopReason::kNone).levels.at(0);
  };
  EXPECT_NEAR(press(SDL_CONTROLLER_BUTTON_DPAD_UP), 0.1, 1e-12);
  EXPECT_NEAR(press(SDL_CONTROLLER_BUTTON_DPAD_UP), 0.2, 1e-12);
  EXPECT_NEAR(press(SDL_CONTROLLER_BUTTON_DPAD_UP, false), 0.2, 1e-12);  // no dead-man
  EXPECT_NEAR(press(SDL_CONTROLLER_BUTTON_DPAD_UP), 0.3, 1e-12);
  EXPECT_NEAR(press(SDL_CONTROLLER_BUTTON_DPAD_UP), 0.3, 1e-12);  // max
  const Demand d = c.Update(in, StopReason::kNone);
  const std::vector<command_t> commands = CommandsFor(plan_, d, true, true);
  ASSERT_EQ(commands.size(), 7u);
  EXPECT_EQ(commands[5].target, "Hip1Motor");
  EXPECT_NEAR(commands[5].values[1], 0.3, 1e-12);
  EXPECT_EQ(commands[6].target, "Knee1Motor");
  EXPECT_NEAR(commands[6].values[1], -0.6, 1e-12);
}

TEST(PacerTest, AtMostOneBatchPerPeriodWhateverTheInputDoes) {
  Pacer pacer(0.1);
  int sent = 0, full = 0;
  // 2 s of input changing every millisecond.
  for (int ms = 0; ms < 2000; ++ms) {
    Demand d;
    d.stop = StopReason::kNone;
    d.wheel_speed = ms * 0.001;
    const Pacer::Batch b = pacer.Due(d, ms * 0.001);
    sent += b.send;
    full += b.send && b.full;
  }
  EXPECT_GE(sent, 19);
  EXPECT_LE(sent, 20);
  EXPECT_LE(full, 3);  // the first and one a second
}

TEST(PacerTest, ChangesGoOutAtOnceAfterAQuietPeriodAndRepeat) {
  Pacer pacer(0.1);
  Demand moving;
  moving.stop = StopReason::kNone;
  Demand stopped;
  stopped.stop = StopReason::kDeadman;
  EXPECT_TRUE(pacer.Due(moving, 0.0).send);
  EXPECT_FALSE(pacer.Due(stopped, 0.05).send);  // within the period: waits
  const Pacer::Batch b = pacer.Due(stopped, 0.1);
  EXPECT_TRUE(b.send && b.changed && b.stop_changed);
  const Pacer::Batch repeat = pacer.Due(stopped, 0.2);
  EXPECT_TRUE(repeat.send);
  EXPECT_FALSE(repeat.changed || repeat.stop_changed);
}

}  // namespace
}  // namespace simpartner::teleop
