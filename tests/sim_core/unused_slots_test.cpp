// The original's three-slot command form on joints that use fewer slots:
// the values in the slots a joint has no axis for set nothing, but they are
// held to the ranges of the used slots, and a refusal names the slot and
// the value. Through the simulation's Submit, as a command from the bus.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "simpartner/command_t.hpp"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeArmSim;

struct UnusedSlotCase {
  const char* name;
  command_t command;
  const char* reason;  // substring of the refusal
};

// "Spin" drives the ArmBot's axle along z (slot z); "ArmMotor" its shoulder,
// also about z. The SPEC's example "1000,1000,100,0,0,0.2" is the form.
std::vector<UnusedSlotCase> UnusedSlotCases() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<UnusedSlotCase> cases;
  auto add = [&](const char* name, command_t c, const char* reason) {
    cases.push_back({name, std::move(c), reason});
  };
  add("1e308 force in the x slot of a wheel",
      Command("Spin", command_t::ACTION_SET, {1e308, 1000, 100, 0, 0, 0.2}),
      "values[0] (max force, x slot, unused: joint 'Axle' has slot z only) = 1e+308 is out of "
      "range [0, 10000000]");
  add("NaN force in the y slot of a wheel",
      Command("Spin", command_t::ACTION_SET, {1000, nan, 100, 0, 0, 0.2}),
      "values[1] = nan is not a finite number (max force, y slot, unused: joint 'Axle' has "
      "slot z only)");
  add("negative force in an unused slot",
      Command("Spin", command_t::ACTION_SET, {-1, 1000, 100, 0, 0, 0.2}),
      "values[0] (max force, x slot, unused");
  add("1e308 velocity in the y slot of a wheel",
      Command("Spin", command_t::ACTION_SET, {1000, 1000, 100, 0, 1e308, 0.2}),
      "values[4] (velocity, y slot, unused: joint 'Axle' has slot z only) = 1e+308 is out of "
      "range [-1000, 1000]");
  add("angle beyond pi in an unused slot of an angle controller",
      Command("ArmMotor", command_t::ACTION_SET, {0, 0, 100, 7, 0, 0.5, 1, 0, 0}),
      "values[3] (target angle, x slot, unused: joint 'Shoulder' has slot z only) = 7 rad is "
      "out of range");
  add("NaN angle in an unused slot of an angle controller",
      Command("ArmMotor", command_t::ACTION_SET, {0, 0, 100, 0, nan, 0.5, 1, 0, 0}),
      "values[4] = nan is not a finite number (target angle, y slot, unused");
  add("1e308 hold force in an unused slot",
      Command("Spin", command_t::ACTION_HOLD, {0, 1e308, 1000}),
      "values[1] (max force, y slot, unused: joint 'Axle' has slot z only) = 1e+308");
  add("1e308 low stop in an unused slot",
      Command("Spin", command_t::ACTION_SET_STOPS, {1e308, 0, 0, 0, -1, 1}),
      "values[0] (low stop, x slot, unused: joint 'Axle' has slot z only) = 1e+308 rad is out "
      "of range");
  return cases;
}

TEST(UnusedSlots, OutOfRangeOrNonFiniteValuesAreRefusedNamingTheSlot) {
  auto sim = MakeArmSim();
  for (const UnusedSlotCase& bad : UnusedSlotCases()) {
    const auto reply = sim->Submit(bad.command);
    ASSERT_TRUE(reply.has_value()) << bad.name << " was accepted";
    EXPECT_FALSE(reply->accepted) << bad.name;
    EXPECT_NE(reply->reason.find(bad.reason), std::string::npos)
        << bad.name << ": reason was '" << reply->reason << "'";
  }
}

// Values in range in the unused slots (the original senders wrote 0 or
// copied the used slot) are still accepted and change nothing.
TEST(UnusedSlots, InRangeValuesAreAcceptedAndIgnored) {
  auto sim = MakeArmSim();
  ASSERT_FALSE(sim->Submit(Command("Spin", command_t::ACTION_SET, {1000, 1000, 100, 0, 0, 0.2})));
  ASSERT_FALSE(
      sim->Submit(Command("Spin", command_t::ACTION_SET, {0, 1e7, 100, -1000, 1000, 0.2})));
  ASSERT_TRUE(sim->Step());
  const auto replies = sim->TakeReplies();
  ASSERT_EQ(replies.size(), 2u);
  EXPECT_TRUE(replies[0].accepted) << replies[0].reason;
  EXPECT_TRUE(replies[1].accepted) << replies[1].reason;
  const ActuatorSetting& s = sim->controller(sim->flat().FindActuator("", "Spin")).setting();
  EXPECT_EQ(s.mode, ControlMode::kVelocity);
  EXPECT_EQ(s.max_force[0], 100.0);
  EXPECT_EQ(s.velocity[0], 0.2);
}

}  // namespace
}  // namespace simpartner::sim
