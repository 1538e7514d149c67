// Materials with mu2, a friction direction and a physical stiffness and
// damping (docs/contacts.md): the good forms parse to what they say, each
// bad value is refused at the line of its element, and a "rolling"
// material needs a body with a spin axis. Lines are found in the XML text
// by a marker, never taken from the loader.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "model_test_support.h"
#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

using testing::LineOf;
using testing::Pose;

// A world with one material written as `material` (on its own lines).
WorldLoadResult WorldWithMaterial(const std::string& material) {
  return ParseWorld("<world>\n" + material + "\n</world>", "contact.xml");
}

// The one diagnostic of a refused world, checked for file, line and words.
void ExpectRefusedAt(const std::string& material, const std::string& marker,
                     const std::vector<std::string>& words) {
  const WorldLoadResult result = WorldWithMaterial(material);
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.file, "contact.xml");
  EXPECT_EQ(d.line, LineOf("<world>\n" + material + "\n</world>", marker)) << d.message;
  for (const std::string& word : words)
    EXPECT_NE(d.message.find(word), std::string::npos) << "'" << word << "' not in: " << d.message;
}

TEST(ContactMaterialLoader, NewFieldsParse) {
  const WorldLoadResult result = WorldWithMaterial(
      "<material name=\"tyre\"><mu>0.5</mu><mu2>1.0</mu2>"
      "<frictionDirection>rolling</frictionDirection>"
      "<stiffness>2e5</stiffness><damping>7000</damping></material>\n"
      "<material name=\"ice\"><mu>0.025</mu></material>");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const Material* tyre = result.world->FindMaterial("tyre");
  ASSERT_NE(tyre, nullptr);
  EXPECT_EQ(tyre->mu, 0.5);
  EXPECT_EQ(tyre->Mu2(), 1.0);
  EXPECT_EQ(tyre->friction_direction, FrictionDirection::kRolling);
  ASSERT_TRUE(tyre->HasStiffness());
  EXPECT_EQ(*tyre->stiffness, 2e5);
  EXPECT_EQ(*tyre->damping, 7000.0);
  // What ice does not say: isotropic, along the slip, softness per step.
  const Material* ice = result.world->FindMaterial("ice");
  ASSERT_NE(ice, nullptr);
  EXPECT_FALSE(ice->mu2.has_value());
  EXPECT_EQ(ice->Mu2(), 0.025);
  EXPECT_EQ(ice->friction_direction, FrictionDirection::kSlip);
  EXPECT_FALSE(ice->HasStiffness());
}

TEST(ContactMaterialLoader, NegativeMu2) {
  ExpectRefusedAt("<material name=\"m\"><mu>0.5</mu>\n<mu2>-0.1</mu2></material>", "<mu2>",
                  {"material 'm'", "mu2", "-0.1", "out of range"});
}

// mu2 is read across a rolling direction only: across the slip it held a
// slide from turning (docs/contacts.md). Said or by default, slip is refused.
TEST(ContactMaterialLoader, Mu2AlongTheSlipIsRefused) {
  ExpectRefusedAt("<material name=\"m\"><mu>0.5</mu>\n<mu2>1.0</mu2></material>", "<mu2>",
                  {"material 'm'", "mu2 1", "mu 0.5", "frictionDirection rolling"});
  ExpectRefusedAt("<material name=\"m\"><mu>0.5</mu>\n<mu2>0.2</mu2>"
                  "<frictionDirection>slip</frictionDirection></material>",
                  "<mu2>", {"material 'm'", "mu2 0.2", "slip"});
  // The same coefficient twice is isotropic, and a rolling material keeps mu2.
  EXPECT_TRUE(WorldWithMaterial("<material name=\"m\"><mu>0.5</mu><mu2>0.5</mu2></material>").world);
  EXPECT_TRUE(WorldWithMaterial("<material name=\"m\"><mu>0.5</mu><mu2>1.0</mu2>"
                                "<frictionDirection>rolling</frictionDirection></material>")
                  .world);
}

TEST(ContactMaterialLoader, UnknownFrictionDirection) {
  ExpectRefusedAt("<material name=\"m\">\n<frictionDirection>sideways</frictionDirection>"
                  "</material>",
                  "<frictionDirection>", {"material 'm'", "'sideways'", "slip, rolling"});
}

TEST(ContactMaterialLoader, StiffnessBesideSoftErp) {
  ExpectRefusedAt("<material name=\"m\"><softERP>0.1</softERP>\n"
                  "<stiffness>1e5</stiffness><damping>100</damping></material>",
                  "<stiffness>", {"material 'm'", "softERP/softCFM", "stiffness/damping"});
}

TEST(ContactMaterialLoader, ZeroStiffness) {
  ExpectRefusedAt("<material name=\"m\">\n<stiffness>0</stiffness><damping>100</damping>"
                  "</material>",
                  "<stiffness>", {"material 'm'", "stiffness 0", "(0, 1e+12]"});
}

TEST(ContactMaterialLoader, NegativeDamping) {
  ExpectRefusedAt("<material name=\"m\"><stiffness>1e5</stiffness>\n<damping>-5</damping>"
                  "</material>",
                  "<damping>", {"material 'm'", "damping -5", "out of range"});
}

TEST(ContactMaterialLoader, StiffnessWithoutDamping) {
  ExpectRefusedAt("<material name=\"m\">\n<stiffness>1e5</stiffness></material>", "<stiffness>",
                  {"material 'm'", "stiffness without damping"});
}

// ------------------------------------------------------------ rolling

// Robot: a box chassis with a wheel of `wheel_type` on a hinge `axis`,
// the wheel of material "tyre" (rolling).
std::string WheelRobot(const std::string& wheel_type, const std::string& hinge) {
  return "<robot name=\"Cart\">\n"
         "<material name=\"tyre\"><mu>0.8</mu><mu2>0.4</mu2>"
         "<frictionDirection>rolling</frictionDirection></material>\n"
         "<body type=\"Box\" name=\"Chassis\"><mass>10</mass>"
         "<size><x>1</x><y>0.2</y><z>0.5</z></size>" + Pose(0, 0.5, 0) + "</body>\n"
         "<body type=\"" + wheel_type + "\" name=\"Wheel\" material=\"tyre\"><mass>1</mass>" +
         (wheel_type == "Box" ? "<size><x>0.3</x><y>0.3</y><z>0.1</z></size>"
                              : "<radius>0.15</radius>" +
                                    std::string(wheel_type == "Sphere" ? "" : "<length>0.1</length>")) +
         Pose(0, 0.15, 0.3) + "</body>\n" + hinge + "</robot>";
}

const char* kAxle =
    "<joint type=\"Hinge\" name=\"Axle\"><body1>Chassis</body1><body2>Wheel</body2>"
    "<anchor><x>0</x><y>0.15</y><z>0.3</z></anchor><axis1><x>0</x><y>0</y><z>1</z></axis1>"
    "</joint>\n";
const char* kWeld =
    "<joint type=\"Fixed\" name=\"Weld\"><body1>Chassis</body1><body2>Wheel</body2></joint>\n";

TEST(ContactMaterialLoader, RollingOnAHingedBodyOrACylinderLoads) {
  for (const auto& [type, joint] : {std::pair<std::string, const char*>{"Sphere", kAxle},
                                    {"Cylinder", kWeld}, {"Box", kAxle}}) {
    SCOPED_TRACE(type);
    const RobotLoadResult result = ParseRobot(WheelRobot(type, joint), "cart.xml");
    ASSERT_TRUE(result.robot) << result.diagnostics.Format();
    const Body* wheel = result.robot->FindBody("Wheel");
    ASSERT_NE(wheel, nullptr);
    const auto axis = SpinAxis(*wheel, result.robot->joints);
    ASSERT_TRUE(axis.has_value());
    // The hinge's z, or the cylinder's own axis (body z).
    EXPECT_TRUE(axis->isApprox(Eigen::Vector3d::UnitZ(), 1e-12)) << axis->transpose();
  }
}

TEST(ContactMaterialLoader, RollingOnABoxWithoutAHingeIsRefusedAtTheBody) {
  const std::string xml = WheelRobot("Box", kWeld);
  const RobotLoadResult result = ParseRobot(xml, "cart.xml");
  EXPECT_FALSE(result.robot);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.file, "cart.xml");
  EXPECT_EQ(d.line, LineOf(xml, "name=\"Wheel\""));
  EXPECT_NE(d.message.find("'Wheel'"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("rolling"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("no spin axis"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("cart.xml:2"), std::string::npos) << d.message;  // the material
}

// The axis is in the body frame: a wheel turned 90 degrees about y (its z
// along world +x, its x along world -z) on a hinge along world z spins
// about its own -x.
TEST(ContactMaterialLoader, SpinAxisOfATurnedBodyIsInItsOwnFrame) {
  Body wheel;
  wheel.name = "Wheel";
  wheel.geometry.kind = GeometryKind::kSphere;
  wheel.pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Joint hinge;
  hinge.name = "Axle";
  hinge.kind = JointKind::kHinge;
  hinge.body1 = "Chassis";
  hinge.body2 = "Wheel";
  hinge.axis[0] = Eigen::Vector3d::UnitZ();
  const auto axis = SpinAxis(wheel, {hinge});
  ASSERT_TRUE(axis.has_value());
  EXPECT_TRUE(axis->isApprox(-Eigen::Vector3d::UnitX(), 1e-12)) << axis->transpose();
  // Two hinges on a sphere: which one rolls it is not known.
  Joint second = hinge;
  second.name = "Other";
  std::string why;
  EXPECT_FALSE(SpinAxis(wheel, {hinge, second}, &why).has_value());
  EXPECT_NE(why.find("Axle, Other"), std::string::npos) << why;
}

// A world's own "rolling" material on a robot's box: refused at the body
// in the robot file, naming the world's material.
TEST(ContactMaterialLoader, WorldRollingMaterialOnARobotBoxIsRefused) {
  const std::string robot =
      "<robot name=\"Crate\">\n<body type=\"Box\" name=\"Crate\" material=\"grip\"><mass>1</mass>"
      "<size><x>1</x><y>1</y><z>1</z></size>" + Pose(0, 0.5, 0) + "</body>\n</robot>";
  const std::string world =
      "<world>\n<material name=\"grip\"><frictionDirection>rolling</frictionDirection>"
      "</material>\n<robot name=\"C\" file=\"crate.xml\"/>\n</world>";
  const FileReader reader = [&](const std::string& path, std::string* out) {
    if (path != "crate.xml") return false;
    *out = robot;
    return true;
  };
  const WorldLoadResult result = ParseWorld(world, "w.xml", reader);
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.file, "crate.xml");
  EXPECT_EQ(d.line, LineOf(robot, "name=\"Crate\" material"));
  EXPECT_NE(d.message.find("w.xml:2"), std::string::npos) << d.message;
}

}  // namespace
}  // namespace simpartner::model
