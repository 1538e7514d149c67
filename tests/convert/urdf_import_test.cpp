// URDF to our robot XML: the result loads with our loader and keeps the
// URDF's masses, links and joints; bad input is refused at its line; a
// converted cart drives in our sim. Expected numbers are read off the test
// URDFs in tests/convert/data (their comments give them).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "simpartner/command_t.hpp"
#include "simpartner/convert/convert.h"
#include "simpartner/convert/urdf_import.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"
#include "../support/text_file.h"

namespace simpartner::convert {
namespace {

const std::string kData = std::string(SP_SOURCE_DIR) + "/tests/convert/data/";

using test_support::ReadText;

// The error a conversion of path throws, as the user reads it.
std::string ConversionError(const std::string& path, UrdfImportOptions options = {}) {
  try {
    ImportUrdf(ReadText(path), path, options);
  } catch (const ConvertError& error) {
    return error.what();
  }
  return "(no error)";
}

model::Robot ConvertAndLoad(const std::string& urdf) {
  const UrdfImportResult result = ImportUrdf(ReadText(kData + urdf), kData + urdf);
  model::RobotLoadResult loaded = model::ParseRobot(result.robot_xml, urdf + ".xml");
  EXPECT_TRUE(loaded.robot) << loaded.diagnostics.Format();
  return *loaded.robot;
}

TEST(UrdfImport, ArmKeepsMassesLinksAndJoints) {
  const model::Robot robot = ConvertAndLoad("arm.urdf");
  // arm.urdf: 2 + 1.5 + 0.5 + 0.25 + 0.1 kg in five links.
  EXPECT_NEAR(robot.TotalMass(), 4.35, 1e-12);
  ASSERT_EQ(robot.bodies.size(), 5u);
  std::map<std::string, model::JointKind> kinds;
  for (const model::Joint& joint : robot.joints) kinds[joint.name] = joint.kind;
  const std::map<std::string, model::JointKind> expected = {
      {"shoulder", model::JointKind::kHinge},
      {"slide", model::JointKind::kSlider},
      {"wrist", model::JointKind::kHinge},
      {"tool_mount", model::JointKind::kFixed}};
  EXPECT_EQ(kinds, expected);
  // Limits as written; the continuous wrist is free.
  const model::Joint* shoulder = robot.FindJoint("shoulder");
  EXPECT_DOUBLE_EQ(shoulder->lo_stop[0], -1.5);
  EXPECT_DOUBLE_EQ(shoulder->hi_stop[0], 1.5);
  const model::Joint* slide = robot.FindJoint("slide");
  EXPECT_DOUBLE_EQ(slide->lo_stop[0], -0.1);
  EXPECT_DOUBLE_EQ(slide->hi_stop[0], 0.2);
  EXPECT_TRUE(std::isinf(robot.FindJoint("wrist")->hi_stop[0]));
  // Every movable joint has its motor.
  EXPECT_EQ(robot.actuators.size(), 3u);
  EXPECT_EQ(robot.bodies[0].geometry.kind, model::GeometryKind::kBox);
  EXPECT_EQ(robot.FindBody("upper")->geometry.kind, model::GeometryKind::kCylinder);
  EXPECT_EQ(robot.FindBody("hand")->geometry.kind, model::GeometryKind::kSphere);
  EXPECT_EQ(robot.FindBody("tool")->geometry.kind, model::GeometryKind::kNone);
}

// URDF z-up becomes y-up: heights (URDF z) are our y, URDF +y (left) is
// our -z, and directions turn the same way.
TEST(UrdfImport, ZUpBecomesYUp) {
  const model::Robot robot = ConvertAndLoad("arm.urdf");
  // upper: collision centre 0.1 (shoulder) + 0.25 above the base origin.
  EXPECT_NEAR(robot.FindBody("upper")->pose.translation().y(), 0.35, 1e-12);
  // The cylinder's axis (its z) pointed up in the URDF: up is our +y.
  const Eigen::Vector3d cylinder_axis =
      robot.FindBody("upper")->pose.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(cylinder_axis.y(), 1.0, 1e-12);
  // The shoulder turns about URDF +y (left), our -z.
  const Eigen::Vector3d shoulder_axis = robot.FindJoint("shoulder")->axis[0];
  EXPECT_NEAR(shoulder_axis.z(), -1.0, 1e-12);
  // The slide runs along x, which stays x; the wrist about up, our y.
  EXPECT_NEAR(robot.FindJoint("slide")->axis[0].x(), 1.0, 1e-12);
  EXPECT_NEAR(robot.FindJoint("wrist")->axis[0].y(), 1.0, 1e-12);
  // The wrist's anchor at 0.1 + 0.55 + 0.1 m height.
  EXPECT_NEAR(robot.FindJoint("wrist")->anchor.y(), 0.75, 1e-12);
}

TEST(UrdfImport, MeshIsRefusedNamingTheLink) {
  const std::string error = ConversionError(kData + "mesh_link.urdf");
  // Line 10 is the link's <collision>.
  EXPECT_NE(error.find("mesh_link.urdf:10: link 'body': mesh collision shape"), std::string::npos)
      << error;
  EXPECT_NE(error.find("--mesh-as-box"), std::string::npos) << error;
}

TEST(UrdfImport, MeshAsBoxUsesTheBoundingBox) {
  UrdfImportOptions options;
  options.mesh_as_box = true;
  const std::string path = kData + "mesh_link.urdf";
  const UrdfImportResult result = ImportUrdf(ReadText(path), path, options);
  model::RobotLoadResult loaded = model::ParseRobot(result.robot_xml, "mesh.xml");
  ASSERT_TRUE(loaded.robot) << loaded.diagnostics.Format();
  const model::Body& body = loaded.robot->bodies.at(0);
  // block.stl spans x 0..0.2, y -0.2..0.2, z 0..0.6 (the body keeps the
  // mesh's own axes).
  EXPECT_EQ(body.geometry.kind, model::GeometryKind::kBox);
  EXPECT_NEAR(body.geometry.size.x(), 0.2, 1e-12);
  EXPECT_NEAR(body.geometry.size.y(), 0.4, 1e-12);
  EXPECT_NEAR(body.geometry.size.z(), 0.6, 1e-12);
  // Centred at (0.1, 0, 0.3) URDF: our (0.1, 0.3, 0).
  EXPECT_NEAR(body.pose.translation().x(), 0.1, 1e-12);
  EXPECT_NEAR(body.pose.translation().y(), 0.3, 1e-12);
  EXPECT_NEAR(body.pose.translation().z(), 0.0, 1e-12);
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("bounding box"), std::string::npos);
}

TEST(UrdfImport, MeshAsBoxSaysWhenItCannot) {
  const std::string dir = testing::TempDir() + "convert_mesh_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  std::string urdf = ReadText(kData + "mesh_link.urdf");
  urdf.replace(urdf.find("meshes/block.stl"), 16, "meshes/block.dae");
  const std::string path = dir + "/dae.urdf";
  std::ofstream(path) << urdf;
  UrdfImportOptions options;
  options.mesh_as_box = true;
  const std::string error = ConversionError(path, options);
  EXPECT_NE(error.find("dae.urdf:10: link 'body': cannot use the bounding box of mesh"),
            std::string::npos)
      << error;
  std::filesystem::remove_all(dir);
}

TEST(UrdfImport, MalformedXmlGivesFileAndLine) {
  const std::string error = ConversionError(kData + "malformed.urdf");
  // <inertial> opened on line 7 is closed by </link> on line 8.
  EXPECT_EQ(error.rfind(kData + "malformed.urdf:8: not well-formed XML: ", 0), 0u) << error;
}

TEST(UrdfImport, UrdfdomRefusalPointsAtTheJoint) {
  const std::string error = ConversionError(kData + "missing_link.urdf");
  // The joint naming the missing link starts on line 7.
  EXPECT_EQ(error.rfind(kData + "missing_link.urdf:7: ", 0), 0u) << error;
  EXPECT_NE(error.find("nowhere"), std::string::npos) << error;
}

TEST(UrdfImport, MasslessLinkIsRefusedAtItsLine) {
  const std::string urdf =
      "<robot name='r'>\n"
      "  <link name='base_footprint'/>\n"
      "  <link name='body'><inertial><mass value='1'/>"
      "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link>\n"
      "  <joint name='j' type='fixed'><parent link='base_footprint'/><child link='body'/></joint>\n"
      "</robot>\n";
  try {
    ImportUrdf(urdf, "inline.urdf");
    FAIL() << "converted a massless link";
  } catch (const ConvertError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("inline.urdf:2: link 'base_footprint' has no "
                                              "<inertial>", 0),
              0u)
        << error.what();
  }
}

TEST(UrdfImport, ProgramWritesTheRobotAndReportsErrors) {
  const std::string out = testing::TempDir() + "arm_" + std::to_string(getpid()) + ".xml";
  std::ostringstream stdout_text, stderr_text;
  EXPECT_EQ(RunConvert({kData + "arm.urdf", "-o", out}, stdout_text, stderr_text), 0)
      << stderr_text.str();
  EXPECT_TRUE(model::LoadRobotFile(out).robot);
  std::filesystem::remove(out);
  std::ostringstream help, none;
  EXPECT_EQ(RunConvert({"--help"}, help, none), 0);
  EXPECT_NE(help.str().find("Usage: simpartner-convert [options] -o OUT IN"), std::string::npos);
  std::ostringstream bad_out, bad_err;
  EXPECT_EQ(RunConvert({kData + "malformed.urdf", "-o", out}, bad_out, bad_err), 1);
  EXPECT_EQ(bad_err.str().rfind(kData + "malformed.urdf:8:", 0), 0u) << bad_err.str();
  EXPECT_EQ(RunConvert({kData + "arm.urdf"}, bad_out, bad_err), 2);
}

// The cart of wheeled_robot.urdf, converted, placed on flat ground with its
// wheels touching, rolls forward at r * omega when its four wheel motors
// turn at omega.
TEST(UrdfImport, ConvertedCartDrivesForward) {
  const std::string dir = testing::TempDir() + "convert_cart_" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  std::ostringstream out, err;
  ASSERT_EQ(RunConvert({kData + "wheeled_robot.urdf", "-o", dir + "/cart.xml"}, out, err), 0)
      << err.str();
  // Axles at the chassis origin, wheels r = 0.1: the origin 0.1 m up.
  std::ofstream(dir + "/cart_world.xml")
      << "<world name='CartWorld'>\n"
         "  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>\n"
         "  <surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n"
         "  <robot name='Cart' file='cart.xml'><transformation>\n"
         "    <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>\n"
         "    <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.1</T13>\n"
         "    <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>\n"
         "  </transformation></robot>\n"
         "</world>\n";
  model::WorldLoadResult world = model::LoadWorldFile(dir + "/cart_world.xml");
  ASSERT_TRUE(world.world) << world.diagnostics.Format();
  sim::Simulation sim(*world.world, Parameters{}, 1);
  const int chassis = sim.flat().FindBody("Cart", "chassis");
  ASSERT_GE(chassis, 0);
  for (int n = 0; n < 500; ++n) ASSERT_TRUE(sim.Step());  // settle
  const Eigen::Vector3d start = sim.engine().ReadBody(chassis).position;
  const double omega = 5.0;  // [rad/s]
  for (const char* motor : {"axle_flMotor", "axle_frMotor", "axle_rlMotor", "axle_rrMotor"}) {
    command_t command{};
    command.robot = "Cart";
    command.target = motor;
    command.action = command_t::ACTION_SET;
    command.apply_at_step = -1;  // at once
    command.values = {100, omega};  // max torque, velocity (per-axis form)
    command.num_values = 2;
    const auto refused = sim.Submit(command);
    ASSERT_FALSE(refused) << motor << ": " << refused->reason;
  }
  const int steps = 2000;
  for (int n = 0; n < steps; ++n) ASSERT_TRUE(sim.Step());
  const Eigen::Vector3d moved = sim.engine().ReadBody(chassis).position - start;
  // 0.1 m * 5 rad/s = 0.5 m/s for 2 s (less the spin-up of some ms).
  EXPECT_NEAR(moved.x(), 1.0, 0.05);
  EXPECT_NEAR(moved.z(), 0.0, 0.01);  // straight
  EXPECT_NEAR(moved.y(), 0.0, 0.01);  // on its wheels
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace simpartner::convert
