// --robot (model/robot_choice.h): a shipped robot by name or a file, put
// into a world at the world's robot pose or a given one, replacing or
// beside the world's robots; wrong names and poses are refused clearly.
#include "simpartner/model/robot_choice.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

namespace fs = std::filesystem;

World Shipped(const std::string& world) {
  return LoadWorldOrThrow((fs::path(SP_SOURCE_DIR) / "models/worlds" / world).string());
}

std::string Refusal(const RobotChoice& choice, World world) {
  try {
    PlaceRobot(choice, &world);
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(RobotChoice, EveryShortNameIsAShippedRobotFile) {
  ASSERT_EQ(ShippedRobots().size(), 5u);
  for (const char* name : {"gen1", "gen1-light", "gen2", "gen3", "gen4"}) {
    const std::string file = RobotFileOf(name);
    EXPECT_TRUE(fs::is_regular_file(file)) << name << " -> " << file;
    EXPECT_EQ(fs::path(file).parent_path().filename(), "robots") << file;
  }
  EXPECT_EQ(fs::path(RobotFileOf("gen1-light")).filename(), "workpartner_gen1_light.xml");
}

TEST(RobotChoice, ReplacesTheWorldsRobotAtItsPoseKeepingItsName) {
  // maze.xml places its gen3 away from the origin.
  World world = Shipped("maze.xml");
  ASSERT_EQ(world.robots.size(), 1u);
  const Eigen::Isometry3d pose = world.robots[0].placement;
  const std::string name = world.robots[0].name;
  RobotChoice choice;
  choice.robot = "gen4";
  PlaceRobot(choice, &world);
  ASSERT_EQ(world.robots.size(), 1u);
  EXPECT_EQ(world.robots[0].name, name);
  EXPECT_EQ(fs::path(world.robots[0].resolved_file).filename(), "workpartner_gen4.xml");
  EXPECT_EQ(world.robots[0].robot.model_name, LoadRobotOrThrow(RobotFileOf("gen4")).model_name);
  EXPECT_TRUE(world.robots[0].placement.isApprox(pose)) << world.robots[0].placement.matrix();
}

TEST(RobotChoice, AGivenPoseAndYawPlaceTheRobot) {
  World world = Shipped("flat_ground.xml");
  RobotChoice choice;
  choice.robot = "gen1";
  ParseRobotPose("1.5,0.25,-2,90", &choice);
  PlaceRobot(choice, &world);
  ASSERT_EQ(world.robots.size(), 1u);
  const Eigen::Isometry3d& p = world.robots[0].placement;
  EXPECT_TRUE(p.translation().isApprox(Eigen::Vector3d(1.5, 0.25, -2))) << p.matrix();
  // 90 degrees about +y (up): the robot's +x becomes the world's -z.
  EXPECT_TRUE((p.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitZ(), 1e-12))
      << p.matrix();
}

TEST(RobotChoice, AddsBesideTheWorldsRobotsUnderANewName) {
  World world = Shipped("two_spheres.xml");
  const size_t before = world.robots.size();
  RobotChoice choice;
  choice.robot = "gen2";
  choice.add = true;
  PlaceRobot(choice, &world);
  ASSERT_EQ(world.robots.size(), before + 1);
  EXPECT_EQ(world.robots.back().name, "WorkPartner");
  // Two shipped robots share their legacy ports: refused, naming both.
  World gen3 = Shipped("flat_ground.xml");
  const std::string why = Refusal(choice, gen3);
  EXPECT_NE(why.find("command line: --robot: robot 'WorkPartner2'"), std::string::npos) << why;
  EXPECT_NE(why.find("already used by 'WorkPartner/"), std::string::npos) << why;
}

TEST(RobotChoice, AWrongNameGetsADidYouMean) {
  RobotChoice choice;
  choice.robot = "gen5";
  const std::string why = Refusal(choice, Shipped("flat_ground.xml"));
  EXPECT_NE(why.find("command line: --robot: unknown robot 'gen5' (did you mean 'gen"),
            std::string::npos)
      << why;
  EXPECT_NE(why.find("gen1, gen1-light, gen2, gen3, gen4"), std::string::npos) << why;
  choice.robot = "gen1_light";
  EXPECT_NE(Refusal(choice, Shipped("flat_ground.xml")).find("did you mean 'gen1-light'"),
            std::string::npos);
  // A path is looked for as a file, and the paths tried are listed.
  choice.robot = "my/robot.xml";
  const std::string file_why = Refusal(choice, Shipped("flat_ground.xml"));
  EXPECT_NE(file_why.find("my/robot.xml: cannot read robot file: not found; tried:"),
            std::string::npos)
      << file_why;
}

TEST(RobotChoice, BadPosesAreRefusedWithTheValue) {
  RobotChoice choice;
  for (const char* bad : {"1,2", "1,2,3,4,5", "1,x,3", "1,,3", "1,2,1e9"}) {
    try {
      ParseRobotPose(bad, &choice);
      ADD_FAILURE() << bad << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("command line: --robot-pose: "), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace simpartner::model
