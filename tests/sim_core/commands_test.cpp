// Bad commands are refused with a reason naming the field and value, and
// change nothing; the same inputs give the same trajectory; reset restores
// step 0; an exploding state is caught in the step it happens.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simpartner/command_t.hpp"
#include "../support/encode.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeArmSim;

// State encoded without the wall-clock and id fields, for comparisons.
std::vector<uint8_t> PhysicsBytes(const Simulation& sim) {
  state_t state;
  sim.FillState(&state);
  state.utime = 0;
  state.simulation_id = 0;
  return test_support::Encode(state);
}

struct BadCase {
  const char* name;
  command_t command;
  const char* reason;  // substring the reason must contain
};

std::vector<BadCase> BadCommands() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<BadCase> cases;
  auto add = [&](const char* name, command_t c, const char* reason) {
    cases.push_back({name, std::move(c), reason});
  };
  add("unknown target", Command("NoSuchMotor", command_t::ACTION_SET, {1000, 1}),
      "target 'NoSuchMotor' is not an actuator or sensor");
  command_t port = Command("", command_t::ACTION_SET, {1000, 1});
  port.port = 4000;
  add("unknown port", port, "port 4000 is not an actuator or sensor");
  command_t low_port = port;
  low_port.port = 80;
  add("port out of range", low_port, "port 80 is out of range");
  command_t both = Command("Spin", command_t::ACTION_SET, {1000, 1});
  both.port = 1028;
  add("name and port", both, "use one");
  add("wrong count", Command("Spin", command_t::ACTION_SET, {1, 2, 3}),
      "expected 6 values (three slots x, y, z) or 2 (per axis), got 3");
  add("NaN", Command("Spin", command_t::ACTION_SET, {1000, nan}), "values[1] = nan is not a finite");
  add("inf", Command("Spin", command_t::ACTION_SET, {inf, 1}), "values[0] = inf is not a finite");
  add("negative force", Command("Spin", command_t::ACTION_SET, {-5, 1}),
      "values[0] (max force) = -5 is out of range");
  add("huge velocity", Command("Spin", command_t::ACTION_SET, {10, 5000}),
      "values[1] (velocity) = 5000 is out of range");
  add("angle beyond pi", Command("ArmMotor", command_t::ACTION_SET, {10, 4.0, 1, 0, 0}),
      "values[1] (target angle) = 4 rad is outside [-pi, pi]");
  add("negative gain", Command("ArmMotor", command_t::ACTION_SET, {10, 0.5, -1, 0, 0}),
      "values[2] (P gain) = -1 is out of range");
  add("stop outside range", Command("Spin", command_t::ACTION_SET_STOPS, {-4, 1}),
      "values[0] (low stop) = -4 rad is outside [-pi, pi]");
  add("stops reversed", Command("Spin", command_t::ACTION_SET_STOPS, {1, -1}),
      "values[0] (low stop) = 1 is above values[1] (high stop) = -1");
  add("past step", Command("Spin", command_t::ACTION_SET, {1000, 1}, 2), "has passed");
  add("bad step", Command("Spin", command_t::ACTION_SET, {1000, 1}, -7), "apply_at_step = -7");
  command_t mismatch = Command("Spin", command_t::ACTION_SET, {1000, 1});
  mismatch.num_values = 5;
  add("count field mismatch", mismatch, "num_values = 5 does not match 2 values");
  command_t text = Command("Spin", command_t::ACTION_SET, {});
  text.text = "1000,abc";
  add("bad text", text, "text value 2 'abc' is not a number");
  add("sensor set", Command("ArmPosition", command_t::ACTION_SET, {1}),
      "only an Echo sensor takes a SET");
  add("sensor rate", Command("ArmPosition", command_t::ACTION_SENSOR_PARAMS, {-3}),
      "values[0] (rate) = -3 Hz is out of range");
  add("actuator read", Command("Spin", command_t::ACTION_READ, {}),
      "action 4 does not apply to an actuator");
  command_t robot = Command("Spin", command_t::ACTION_SET, {1000, 1});
  robot.robot = "Nobody";
  add("unknown robot", robot, "robot 'Nobody' does not exist");
  command_t elsewhere = Command("Spin", command_t::ACTION_SET, {1000, 1});
  elsewhere.simulation_id = 2;  // MakeSim's simulation is 1
  add("another simulation", elsewhere,
      "simulation_id = 2: the command is meant for another simulation (this one is 1)");
  return cases;
}

TEST(Commands, BadCommandsAreRefusedAndChangeNothing) {
  auto sim = MakeArmSim();
  auto twin = MakeArmSim();
  for (int n = 0; n < 10; ++n) {
    ASSERT_TRUE(sim->Step());
    ASSERT_TRUE(twin->Step());
  }
  for (const BadCase& bad : BadCommands()) {
    const auto reply = sim->Submit(bad.command);
    ASSERT_TRUE(reply.has_value()) << bad.name << " was accepted";
    EXPECT_FALSE(reply->accepted) << bad.name;
    EXPECT_NE(reply->reason.find(bad.reason), std::string::npos)
        << bad.name << ": reason was '" << reply->reason << "'";
    EXPECT_EQ(reply->request_id, bad.command.request_id);
  }
  for (int n = 0; n < 200; ++n) {
    ASSERT_TRUE(sim->Step());
    ASSERT_TRUE(twin->Step());
  }
  EXPECT_TRUE(sim->TakeReplies().empty());
  EXPECT_EQ(PhysicsBytes(*sim), PhysicsBytes(*twin));
}

// A command for simulation 0 (any) or for this one (1) is applied; one for
// another simulation (and for this one before its reset) is refused.
TEST(Commands, TheSimulationIdIsZeroOrThisSimulations) {
  auto sim = MakeArmSim();
  for (const int64_t id : {int64_t{0}, int64_t{1}}) {
    command_t c = Command("Spin", command_t::ACTION_SET, {1000, 0.5 + static_cast<double>(id)});
    c.simulation_id = id;
    c.request_id = 10 + id;
    EXPECT_FALSE(sim->Submit(c).has_value()) << "simulation_id " << id;
    ASSERT_TRUE(sim->Step());
    const auto replies = sim->TakeReplies();
    ASSERT_EQ(replies.size(), 1u) << "simulation_id " << id;
    EXPECT_TRUE(replies[0].accepted) << replies[0].reason;
    EXPECT_EQ(replies[0].request_id, 10 + id);
    EXPECT_EQ(replies[0].simulation_id, 1);
  }
  sim->Reset(7);
  command_t stale = Command("Spin", command_t::ACTION_SET, {1000, 1});
  stale.simulation_id = 1;
  const auto refusal = sim->Submit(stale);
  ASSERT_TRUE(refusal.has_value());
  EXPECT_FALSE(refusal->accepted);
  EXPECT_EQ(refusal->simulation_id, 7);
  EXPECT_EQ(refusal->reason,
            "simulation_id = 1: the command is meant for another simulation (this one is 7)");
  stale.simulation_id = 7;
  EXPECT_FALSE(sim->Submit(stale).has_value());
}

// The same timed commands give the same trajectory, bit for bit.
TEST(Determinism, SameInputsSameStateStream) {
  auto run = [](const std::string& stepper) {
    Parameters params;
    params.stepper = stepper;
    auto sim = MakeArmSim(-9.81, params);
    sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 5.0}, 10));
    sim->Submit(Command("ArmMotor", command_t::ACTION_SET, {50, 1.0, 4, 1, 0.1}, 300));
    sim->Submit(Command("ArmMotor", command_t::ACTION_SET, {50, -1.0, 4, 1, 0.1}, 900));
    std::vector<uint8_t> stream;
    for (int n = 0; n < 1500; ++n) {
      sim->Step();
      const std::vector<uint8_t> bytes = PhysicsBytes(*sim);
      stream.insert(stream.end(), bytes.begin(), bytes.end());
    }
    return stream;
  };
  for (const char* stepper : {"accurate", "quick"}) {
    const auto a = run(stepper);
    const auto b = run(stepper);
    EXPECT_EQ(a.size(), b.size());
    EXPECT_TRUE(a == b) << stepper << ": the two runs differ";
  }
}

TEST(Reset, BackToTheInitialState) {
  auto sim = MakeArmSim();
  const auto initial = PhysicsBytes(*sim);
  sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 5.0}));
  sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 1.0}, 5000));
  for (int n = 0; n < 500; ++n) sim->Step();
  EXPECT_NE(PhysicsBytes(*sim), initial);
  sim->Reset(2);
  EXPECT_EQ(sim->step(), 0);
  EXPECT_EQ(sim->simulation_id(), 2);
  EXPECT_EQ(PhysicsBytes(*sim), initial);
  // The pending command for step 5000 is gone and the wheel holds again.
  for (int n = 0; n < 100; ++n) sim->Step();
  EXPECT_NEAR(sim->engine().JointRate(sim->flat().FindJoint("", "Axle"), 0), 0.0, 1e-9);
  EXPECT_EQ(sim->controller(sim->flat().FindActuator("", "Spin")).setting().mode,
            ControlMode::kHold);
}

// A body thrown beyond maxLinearVelocity is an explosion: caught in the
// step it happens, named, and the sim stops stepping.
TEST(Health, ExplosionIsDetectedAndNamed) {
  using testing::Transform;
  const std::string world =
      "<world><gravity><x>0</x><y>0</y><z>0</z></gravity>"
      "<object type=\"Sphere\" name=\"Bullet\"><mass>1</mass><radius>0.1</radius>" +
      Transform(0, 5, 0) +
      "<translationalVelocity><vx>0</vx><vy>0</vy><vz>0</vz></translationalVelocity></object>"
      "<object type=\"Sphere\" name=\"Calm\"><mass>1</mass><radius>0.1</radius>" +
      Transform(3, 5, 0) + "</object></world>";
  Parameters params;
  params.maxLinearVelocity = 100;
  auto sim = testing::MakeSim(world, {}, params);
  for (int n = 0; n < 10; ++n) ASSERT_TRUE(sim->Step());
  // 1e6 N on 1 kg for one 1 ms step: 1000 m/s.
  sim->engine().AddForce(0, Eigen::Vector3d(1e6, 0, 0));
  EXPECT_FALSE(sim->Step());
  EXPECT_TRUE(sim->faulted());
  EXPECT_EQ(sim->step(), 11);
  EXPECT_FALSE(sim->Step());  // no more steps until reset
  EXPECT_EQ(sim->step(), 11);
  const auto warnings = sim->TakeWarnings();
  ASSERT_FALSE(warnings.empty());
  const warning_t& w = warnings.back();
  EXPECT_EQ(w.severity, warning_t::SEVERITY_ERROR);
  EXPECT_EQ(w.step, 11);
  ASSERT_EQ(w.bodies.size(), 1u);
  EXPECT_EQ(w.bodies[0], "Bullet");
  EXPECT_NE(w.message.find("maxLinearVelocity 100"), std::string::npos) << w.message;
  sim->Reset(3);
  EXPECT_TRUE(sim->Step());
}

TEST(Model, MessageDescribesEveryPart) {
  auto sim = MakeArmSim();
  model_t m;
  sim->FillModel(&m);
  EXPECT_EQ(m.num_robots, 1);
  EXPECT_EQ(m.robots[0].name, "Bot");
  EXPECT_DOUBLE_EQ(m.robots[0].total_mass, 1002.0);
  ASSERT_EQ(m.num_bodies, 3);
  EXPECT_EQ(m.bodies[1].name, "Arm");
  EXPECT_EQ(m.bodies[1].geometry.kind, geometry_t::KIND_BOX);
  EXPECT_DOUBLE_EQ(m.bodies[1].initial_position[1], 1.5);
  // Box inertia about z: m (lx^2 + ly^2) / 12 = (0.01 + 1) / 12.
  EXPECT_NEAR(m.bodies[1].inertia[2], 1.01 / 12.0, 1e-12);
  ASSERT_EQ(m.num_joints, 2);
  EXPECT_EQ(m.joints[0].body1, 0);
  EXPECT_EQ(m.joints[0].body2, 1);
  EXPECT_DOUBLE_EQ(m.joints[0].axis[0][2], 1.0);
  ASSERT_EQ(m.num_actuators, 2);
  EXPECT_EQ(m.actuators[1].name, "Spin");
  EXPECT_EQ(m.actuators[1].port, 1028);
  EXPECT_EQ(m.actuators[1].axis_slot[0], 2);  // axle along z: the original's third slot
  EXPECT_EQ(m.num_sensors, 3);
  EXPECT_NE(m.parameters.find("stepsize=0.001"), std::string::npos);
}

// Commands dated far ahead wait in a bounded queue: 5,000 of them used to
// take 256 MB. The one past the bound is refused, saying so; the queued
// ones still apply in their step.
TEST(CommandQueueTest, TheQueueOfFutureCommandsIsBoundedAndSaysSo) {
  auto sim = MakeArmSim();
  for (size_t i = 0; i < Simulation::kMaxPendingCommands; ++i) {
    auto refusal = sim->Submit(Command("ArmMotor", command_t::ACTION_HOLD, {1000}, 1000000 + static_cast<int64_t>(i)));
    ASSERT_FALSE(refusal) << "command " << i << ": " << refusal->reason;
  }
  auto refusal = sim->Submit(Command("ArmMotor", command_t::ACTION_HOLD, {1000}, 5));
  ASSERT_TRUE(refusal);
  EXPECT_NE(refusal->reason.find("the queue of commands waiting for their step is full (10000 "
                                 "commands"),
            std::string::npos)
      << refusal->reason;
  // A command for the next step still goes in and applies there (before,
  // every command was refused until a reset).
  EXPECT_FALSE(sim->Submit(Command("ArmMotor", command_t::ACTION_HOLD, {0.5}, -1)));
  EXPECT_FALSE(sim->Submit(Command("ArmMotor", command_t::ACTION_HOLD, {0.25}, 0)));
  ASSERT_TRUE(sim->Step());
  const auto replies = sim->TakeReplies();
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_TRUE(replies[0].accepted && replies[1].accepted);
  EXPECT_EQ(replies[1].applied_at_step, 0);
  // A big text fills the byte bound long before the count bound.
  auto other = MakeArmSim();
  command_t big = Command("ArmMotor", command_t::ACTION_HOLD, {1000}, 2000000);
  big.text = std::string(60000, ' ');
  size_t accepted = 0;
  while (!other->Submit(big)) ++accepted;
  EXPECT_LT(accepted, 300u);  // 16 MiB / 60 kB
  EXPECT_GT(accepted, 250u);
}

// A command from `sender` dated `step`.
command_t From(const std::string& sender, int64_t step) {
  command_t c = Command("ArmMotor", command_t::ACTION_HOLD, {1000}, step);
  c.sender = sender;
  return c;
}

// The queue is shared fairly: one sender's flood (the audit's 10,000
// commands dated far ahead) cannot refuse another's. The other takes the
// room of the flood's latest commands until both hold the same share; the
// flood's dropped commands are answered, saying why.
TEST(CommandQueueTest, OneSendersFloodCannotRefuseAnothersCommands) {
  auto sim = MakeArmSim();
  for (size_t i = 0; i < Simulation::kMaxPendingCommands; ++i)
    ASSERT_FALSE(sim->Submit(From("flood", 1000000 + static_cast<int64_t>(i))));
  auto refused = sim->Submit(From("flood", 5));
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->reason.find("sender 'flood' holds 10000 commands"), std::string::npos)
      << refused->reason;

  ASSERT_FALSE(sim->Submit(From("sequencer", 100)));
  std::vector<command_reply_t> dropped = sim->TakeReplies();
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_FALSE(dropped[0].accepted);
  EXPECT_EQ(dropped[0].sender, "flood");
  EXPECT_NE(dropped[0].reason.find("it was full, sender 'flood' holds 10000 commands"),
            std::string::npos)
      << dropped[0].reason;
  // The flood cannot take it back: it holds more.
  refused = sim->Submit(From("flood", 6));
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->reason.find("sender 'flood' holds 9999 commands"), std::string::npos)
      << refused->reason;
  // The sequencer gets in up to half of the queue, then is refused too.
  for (int i = 1; i < 5000; ++i) ASSERT_FALSE(sim->Submit(From("sequencer", 100 + i))) << i;
  EXPECT_EQ(sim->TakeReplies().size(), 4999u);
  refused = sim->Submit(From("sequencer", 7));
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->reason.find("sender 'sequencer' holds 5000 commands"), std::string::npos)
      << refused->reason;

  // A reset drops every command of the old simulation: a third sender
  // gets in without taking anyone's room.
  sim->Reset(2);
  sim->TakeReplies();
  ASSERT_FALSE(sim->Submit(From("teleop", 1000)));
  EXPECT_TRUE(sim->TakeReplies().empty());
}

}  // namespace
}  // namespace simpartner::sim
