// What teleop's keyboard window says: the keys of a mapping's plan and the
// status line wrapped to the window's width.
#include <gtest/gtest.h>

#include "simpartner/teleop/keyboard_window.h"

namespace simpartner::teleop {
namespace {

TEST(KeyboardWindowTest, HelpNamesTheDeadManTheDrivingKeysAndEachLevel) {
  const std::vector<std::string> fixed = KeyboardHelpLines(nullptr);
  ASSERT_EQ(fixed.size(), 3u);
  EXPECT_EQ(fixed[0], "hold SPACE: dead-man (drives only while held)");
  EXPECT_EQ(fixed[2], "Esc or close the window: stop the wheels and quit");

  Plan plan;
  for (const char* name : {"body", "torso", "claws", "fourth"}) {
    Plan::Level level;
    level.name = name;
    plan.levels.push_back(level);
  }
  const std::vector<std::string> lines = KeyboardHelpLines(&plan);
  // The first three levels have keys (KeyboardInput's R/F, Q/E, O/C); a
  // fourth has none and is not offered.
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(lines[2], "R / F: body up / down");
  EXPECT_EQ(lines[3], "Q / E: torso up / down");
  EXPECT_EQ(lines[4], "O / C: claws up / down");
}

TEST(KeyboardWindowTest, StatusWrapsAtItsSeparators) {
  const std::string status = "WorkPartner gen3 | stopped: dead-man released | wheels +0.00 rad/s";
  const std::vector<std::string> lines = WrapStatus(status, 40);
  // Each part with the next would pass 40 characters (45, then 47).
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "WorkPartner gen3");
  EXPECT_EQ(lines[1], "stopped: dead-man released");
  EXPECT_EQ(lines[2], "wheels +0.00 rad/s");
  EXPECT_EQ(WrapStatus(status, 47), (std::vector<std::string>{
                                        "WorkPartner gen3 | stopped: dead-man released",
                                        "wheels +0.00 rad/s"}));
  EXPECT_EQ(WrapStatus(status, 200), std::vector<std::string>{status});
  // A part longer than a line is cut, never left to run off the window.
  EXPECT_EQ(WrapStatus(std::string(50, 'x'), 20), std::vector<std::string>{std::string(20, 'x')});
  EXPECT_TRUE(WrapStatus("", 20).empty());
}

}  // namespace
}  // namespace simpartner::teleop
