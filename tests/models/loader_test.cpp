// The loader on inline XML: every good form parses to the numbers written
// in it (inertias from the textbook formulas for uniform solids, worked out
// here), and problems come back as typed diagnostics (file, line, element,
// message) at the line of the offending element. Lines are found in the
// XML text by a marker, never taken from the loader.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "model_test_support.h"
#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

constexpr double kTight = 1e-12;

using testing::LineOf;
using testing::Pose;

// Files that exist only in memory, as the FileReader hook allows.
struct MemoryFiles {
  std::map<std::string, std::string> files;
  FileReader Reader() const {
    return [this](const std::string& path, std::string* contents) {
      const auto it = files.find(path);
      if (it == files.end()) return false;
      *contents = it->second;
      return true;
    };
  }
};

const Diagnostic* Find(const DiagnosticList& list, const std::string& element) {
  for (const Diagnostic& d : list.items())
    if (d.element == element) return &d;
  return nullptr;
}

// ------------------------------------------------------------ good forms

// SPEC 3: the original's object, verbatim, in a world that says nothing else.
TEST(LoaderWorld, OriginalObjectFormLoadsUnchanged) {
  const std::string xml = R"(<?xml version="1.0"?>
<world>
    <object type="Body" name="TestParticle">
      <mass>1</mass>
      <transformation>
        <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
        <T10>0</T10><T11>1</T11><T12>0</T12><T13>10</T13>
        <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
      </transformation>
      <translationalVelocity><vx>0</vx><vy>0</vy><vz>0</vz></translationalVelocity>
      <rotationalVelocity><omegax>0</omegax><omegay>0</omegay><omegaz>0</omegaz></rotationalVelocity>
    </object>
</world>
)";
  const WorldLoadResult result = ParseWorld(xml, "original.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  EXPECT_TRUE(result.diagnostics.empty());
  const World& world = *result.world;
  // Not written, so the original's y-up defaults.
  EXPECT_EQ(world.gravity, Eigen::Vector3d(0, -9.81, 0));
  EXPECT_FALSE(world.has_plane);
  EXPECT_TRUE(world.robots.empty());
  ASSERT_EQ(world.objects.size(), 1u);
  const Body& particle = world.objects[0];
  EXPECT_EQ(particle.name, "TestParticle");
  EXPECT_EQ(particle.geometry.kind, GeometryKind::kNone);
  EXPECT_FALSE(particle.is_static);
  EXPECT_EQ(particle.mass, 1.0);
  EXPECT_TRUE(particle.pose.linear().isIdentity(kTight));
  EXPECT_EQ(particle.pose.translation(), Eigen::Vector3d(0, 10, 0));
  EXPECT_EQ(particle.linear_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(particle.angular_velocity, Eigen::Vector3d::Zero());
  // A point mass is given the inertia of a 0.1 m solid sphere:
  // 2/5 m r^2 = 0.4 * 1 * 0.01.
  EXPECT_NEAR(particle.inertia(0, 0), 0.004, kTight);
  EXPECT_NEAR(particle.inertia(1, 1), 0.004, kTight);
  EXPECT_NEAR(particle.inertia(2, 2), 0.004, kTight);
  EXPECT_EQ(particle.where.line, LineOf(xml, "name=\"TestParticle\""));
  EXPECT_EQ(particle.where.file, "original.xml");
}

TEST(LoaderWorld, ObjectVelocitiesAndRotation) {
  // 90 degrees about z (x -> y), thrown at (10, 10, 0), spinning at 1.5 rad/s.
  const std::string xml = R"(<world name="Thrown">
  <object type="Body" name="P">
    <mass>2.5</mass>
    <transformation>
      <T00>0</T00><T01>-1</T01><T02>0</T02><T03>1</T03>
      <T10>1</T10><T11>0</T11><T12>0</T12><T13>2</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>3</T23>
    </transformation>
    <translationalVelocity><vx>10</vx><vy>10</vy><vz>0</vz></translationalVelocity>
    <rotationalVelocity><omegax>0</omegax><omegay>0</omegay><omegaz>1.5</omegaz></rotationalVelocity>
  </object>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "thrown.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const Body& p = result.world->objects.at(0);
  EXPECT_EQ(p.mass, 2.5);
  EXPECT_TRUE((p.pose * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 3, 3), kTight));
  EXPECT_TRUE((p.pose * Eigen::Vector3d(0, 1, 0)).isApprox(Eigen::Vector3d(0, 2, 3), kTight));
  EXPECT_EQ(p.linear_velocity, Eigen::Vector3d(10, 10, 0));
  EXPECT_EQ(p.angular_velocity, Eigen::Vector3d(0, 0, 1.5));
}

// Rounded entries (cos 45 = 0.70710678...) are accepted and made exactly
// orthonormal, so that a body is not sheared by four-digit files.
TEST(LoaderWorld, RoundedRotationIsAcceptedAndOrthonormalised) {
  const std::string xml = R"(<world>
  <object type="Sphere" name="Ball">
    <mass>1</mass>
    <radius>0.1</radius>
    <transformation>
      <T00>0.7071</T00><T01>-0.7071</T01><T02>0</T02><T03>0</T03>
      <T10>0.7071</T10><T11>0.7071</T11><T12>0</T12><T13>0</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </object>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "rounded.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const Eigen::Matrix3d r = result.world->objects.at(0).pose.linear();
  EXPECT_TRUE((r.transpose() * r).isIdentity(1e-12));
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(r(0, 0), std::sqrt(0.5), 1e-4);
  EXPECT_NEAR(r(1, 0), std::sqrt(0.5), 1e-4);
}

// Three decimals (0.707) still load; two (0.71, |R^T R - I| = 8e-3) do not.
TEST(LoaderWorld, ThreeDecimalRotationLoadsTwoDecimalsDoNot) {
  auto world = [](const char* c) {
    return std::string(R"(<world><object type="Sphere" name="Ball"><mass>1</mass>
<radius>0.1</radius><transformation>
<T00>)") + c + "</T00><T01>-" + c + "</T01><T02>0</T02><T03>0</T03><T10>" + c +
           "</T10><T11>" + c + R"(</T11><T12>0</T12><T13>0</T13>
<T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></object></world>)";
  };
  const WorldLoadResult three = ParseWorld(world("0.707"), "three.xml");
  ASSERT_TRUE(three.world) << three.diagnostics.Format();
  EXPECT_NEAR(three.world->objects.at(0).pose.linear().determinant(), 1.0, 1e-12);
  const WorldLoadResult two = ParseWorld(world("0.71"), "two.xml");
  ASSERT_FALSE(two.world);
  ASSERT_EQ(two.diagnostics.size(), 1u);
  EXPECT_EQ(two.diagnostics.items()[0].line, 2);  // <transformation>
  EXPECT_NE(two.diagnostics.items()[0].message.find("not a rotation matrix"), std::string::npos);
}

TEST(LoaderWorld, EachGeometryKindWithItsSolidInertia) {
  const std::string xml = "<world>"
      "<object type=\"Box\" name=\"Crate\"><mass>2</mass>"
      "<size><x>0.3</x><y>0.4</y><z>1.2</z></size>" + Pose(0, 1, 0) + "</object>"
      "<object type=\"Sphere\" name=\"Ball\"><mass>3</mass><radius>0.2</radius>" +
      Pose(1, 1, 0) + "</object>"
      "<object type=\"Cylinder\" name=\"Drum\"><mass>4</mass><radius>0.1</radius>"
      "<length>0.6</length>" + Pose(2, 1, 0) + "</object>"
      "<object type=\"Capsule\" name=\"Pill\"><mass>5</mass><radius>0.1</radius>"
      "<length>0.4</length>" + Pose(3, 1, 0) + "</object>"
      "<object type=\"Box\" name=\"Wall\" static=\"true\">"
      "<size><x>0.2</x><y>3</y><z>20</z></size>" + Pose(6.1, 1.5, 0) + "</object>"
      "</world>";
  const WorldLoadResult result = ParseWorld(xml, "shapes.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const std::vector<Body>& o = result.world->objects;
  ASSERT_EQ(o.size(), 5u);

  // Box 2 kg, 0.3 x 0.4 x 1.2: I = m (b^2 + c^2) / 12.
  EXPECT_EQ(o[0].geometry.kind, GeometryKind::kBox);
  EXPECT_EQ(o[0].geometry.size, Eigen::Vector3d(0.3, 0.4, 1.2));
  EXPECT_NEAR(o[0].inertia(0, 0), 2 * (0.16 + 1.44) / 12, kTight);
  EXPECT_NEAR(o[0].inertia(1, 1), 2 * (0.09 + 1.44) / 12, kTight);
  EXPECT_NEAR(o[0].inertia(2, 2), 2 * (0.09 + 0.16) / 12, kTight);
  EXPECT_FALSE(o[0].inertia_given);

  // Sphere 3 kg, r 0.2: 2/5 m r^2 = 0.048.
  EXPECT_EQ(o[1].geometry.kind, GeometryKind::kSphere);
  EXPECT_EQ(o[1].geometry.size.x(), 0.2);
  EXPECT_NEAR(o[1].inertia(0, 0), 0.048, kTight);
  EXPECT_NEAR(o[1].inertia(2, 2), 0.048, kTight);

  // Cylinder 4 kg, r 0.1, length 0.6 along z: Izz = m r^2 / 2 = 0.02,
  // Ixx = Iyy = m (3 r^2 + l^2) / 12 = 0.13.
  EXPECT_EQ(o[2].geometry.kind, GeometryKind::kCylinder);
  EXPECT_EQ(o[2].geometry.size.x(), 0.1);
  EXPECT_EQ(o[2].geometry.size.y(), 0.6);
  EXPECT_NEAR(o[2].inertia(2, 2), 0.02, kTight);
  EXPECT_NEAR(o[2].inertia(0, 0), 0.13, kTight);
  EXPECT_NEAR(o[2].inertia(1, 1), 0.13, kTight);

  // Capsule 5 kg, r 0.1, cylinder part 0.4: by volume 3.75 kg in the
  // cylinder, 1.25 kg in the two caps. Izz = 3.75 r^2/2 + 1.25 * 2/5 r^2 =
  // 0.02375; Ixx = 3.75 (3 r^2 + l^2)/12 + 1.25 (2/5 r^2 + l^2/4 + 3 l r/8)
  // = 0.059375 + 0.07375.
  EXPECT_EQ(o[3].geometry.kind, GeometryKind::kCapsule);
  EXPECT_NEAR(o[3].inertia(2, 2), 0.02375, 1e-12);
  EXPECT_NEAR(o[3].inertia(0, 0), 0.133125, 1e-12);

  // A static object needs no mass.
  EXPECT_TRUE(o[4].is_static);
  EXPECT_EQ(o[4].mass, 0.0);
  EXPECT_EQ(o[4].geometry.size, Eigen::Vector3d(0.2, 3, 20));
  EXPECT_TRUE(o[4].pose.translation().isApprox(Eigen::Vector3d(6.1, 1.5, 0), kTight));
}

TEST(LoaderWorld, GivenInertiaAndCentreOfMass) {
  const std::string xml = "<world><object type=\"Box\" name=\"Crate\"><mass>2</mass>"
      "<size><x>1</x><y>1</y><z>1</z></size>"
      "<centerOfMass><x>0.1</x><y>-0.2</y><z>0.05</z></centerOfMass>"
      "<inertia><Ixx>0.5</Ixx><Iyy>0.6</Iyy><Izz>0.7</Izz><Ixy>0.01</Ixy><Ixz>-0.02</Ixz>"
      "<Iyz>0.03</Iyz></inertia>" + Pose(0, 0.5, 0) + "</object></world>";
  const WorldLoadResult result = ParseWorld(xml, "inertia.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const Body& b = result.world->objects.at(0);
  EXPECT_TRUE(b.inertia_given);
  EXPECT_EQ(b.com, Eigen::Vector3d(0.1, -0.2, 0.05));
  Eigen::Matrix3d expected;
  expected << 0.5, 0.01, -0.02, 0.01, 0.6, 0.03, -0.02, 0.03, 0.7;
  EXPECT_EQ(b.inertia, expected);
}

TEST(LoaderWorld, GravitySurfaceSpaceAndDescription) {
  const std::string xml = R"(<world name="Moon" version="1">
  <description>Lunar test</description>
  <gravity><x>0</x><y>-1.62</y><z>0</z></gravity>
  <surface material="regolith"><a>0</a><b>2</b><c>0</c><d>4</d></surface>
  <collisionSpace type="quadtree"/>
  <material name="regolith"><mu>0.7</mu></material>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "moon.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const World& w = *result.world;
  EXPECT_EQ(w.name, "Moon");
  EXPECT_EQ(w.description, "Lunar test");
  EXPECT_EQ(w.gravity, Eigen::Vector3d(0, -1.62, 0));
  EXPECT_TRUE(w.Up().isApprox(Eigen::Vector3d(0, 1, 0), kTight));
  // 2y = 4 is the plane y = 2, stored with a unit normal.
  EXPECT_TRUE(w.has_plane);
  EXPECT_TRUE(w.plane.isApprox(Eigen::Vector4d(0, 1, 0, 2), kTight));
  EXPECT_EQ(w.plane_material, "regolith");
  EXPECT_EQ(w.collision_space, CollisionSpaceKind::kQuadTree);
  ASSERT_NE(w.FindMaterial("regolith"), nullptr);
  EXPECT_EQ(w.FindMaterial("regolith")->mu, 0.7);
}

TEST(LoaderWorld, MaterialContactParameters) {
  const std::string xml = R"(<world>
  <collisionSpace type="simple"/>
  <material name="rubber">
    <mu>1.2</mu><bounce>0.6</bounce><bounceVelocity>0.3</bounceVelocity>
    <softERP>0.4</softERP><softCFM>0.002</softCFM><rollingFriction>0.01</rollingFriction>
  </material>
  <material name="ice"><mu>0.025</mu></material>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "materials.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  EXPECT_EQ(result.world->collision_space, CollisionSpaceKind::kSimple);
  const Material* rubber = result.world->FindMaterial("rubber");
  ASSERT_NE(rubber, nullptr);
  EXPECT_EQ(rubber->mu, 1.2);
  EXPECT_EQ(rubber->bounce, 0.6);
  EXPECT_EQ(rubber->bounce_velocity, 0.3);
  EXPECT_EQ(rubber->soft_erp, 0.4);
  EXPECT_EQ(rubber->soft_cfm, 0.002);
  EXPECT_EQ(rubber->rolling_friction, 0.01);
  EXPECT_EQ(rubber->where.line, LineOf(xml, "name=\"rubber\""));
  // What ice does not say is the default material's.
  const Material* ice = result.world->FindMaterial("ice");
  ASSERT_NE(ice, nullptr);
  const Material defaults;
  EXPECT_EQ(ice->mu, 0.025);
  EXPECT_EQ(ice->bounce, defaults.bounce);
  EXPECT_EQ(ice->soft_cfm, defaults.soft_cfm);
}

TEST(LoaderWorld, Heightfield) {
  // 2 rows (z) x 3 columns (x) over 4 m x 2 m, samples in cm.
  const std::string xml = R"(<world>
  <material name="snow"><mu>0.5</mu></material>
  <heightfield rows="2" columns="3" material="snow">
    <width>4</width>
    <depth>2</depth>
    <scale>0.01</scale>
    <offset>-1</offset>
    <thickness>0.5</thickness>
    <position><x>1</x><y>0</y><z>2</z></position>
    <samples>
      <!-- z = -1 -->
      0 100 200
      <!-- z = +1 -->
      300 400 500
    </samples>
  </heightfield>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "field.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  ASSERT_TRUE(result.world->heightfield.has_value());
  const Heightfield& h = *result.world->heightfield;
  EXPECT_EQ(h.rows, 2);
  EXPECT_EQ(h.columns, 3);
  EXPECT_EQ(h.width, 4.0);
  EXPECT_EQ(h.depth, 2.0);
  EXPECT_EQ(h.scale, 0.01);
  EXPECT_EQ(h.offset, -1.0);
  EXPECT_EQ(h.thickness, 0.5);
  EXPECT_EQ(h.position, Eigen::Vector3d(1, 0, 2));
  EXPECT_EQ(h.material, "snow");
  EXPECT_EQ(h.samples, (std::vector<double>{0, 100, 200, 300, 400, 500}));
  // Height = scale * sample + offset: corners and a midpoint.
  EXPECT_NEAR(h.HeightAt(-2, -1), -1.0, kTight);    // sample 0
  EXPECT_NEAR(h.HeightAt(0, -1), 0.0, kTight);      // sample 100
  EXPECT_NEAR(h.HeightAt(2, 1), 4.0, kTight);       // sample 500
  EXPECT_NEAR(h.HeightAt(-1, -1), -0.5, kTight);    // between 0 and 100
  EXPECT_NEAR(h.HeightAt(0, 0), 1.5, kTight);       // between 100 and 400
}

TEST(LoaderWorld, PassiveJointToTheStaticWorld) {
  const std::string xml = "<world><object type=\"Box\" name=\"Gate\"><mass>20</mass>"
      "<size><x>1</x><y>2</y><z>0.05</z></size>" + Pose(0, 1, 0) + "</object>"
      "<joint type=\"Hinge\" name=\"GateHinge\"><body1>Gate</body1><body2>world</body2>"
      "<anchor><x>-0.5</x><y>1</y><z>0</z></anchor><axis1><x>0</x><y>3</y><z>0</z></axis1>"
      "<limits><lo>-1.5</lo><hi>1.5</hi></limits></joint></world>";
  const WorldLoadResult result = ParseWorld(xml, "gate.xml");
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  ASSERT_EQ(result.world->joints.size(), 1u);
  const Joint& j = result.world->joints[0];
  EXPECT_EQ(j.kind, JointKind::kHinge);
  EXPECT_EQ(j.body1, "Gate");
  EXPECT_EQ(j.body2, "world");
  EXPECT_EQ(j.anchor, Eigen::Vector3d(-0.5, 1, 0));
  EXPECT_TRUE(j.axis[0].isApprox(Eigen::Vector3d(0, 1, 0), kTight));  // normalised
  EXPECT_EQ(j.lo_stop[0], -1.5);
  EXPECT_EQ(j.hi_stop[0], 1.5);
}

// ------------------------------------------------------------ robots

// A robot with every joint kind, sensor kind and actuator kind.
const char* const kFullRobot = R"(<robot name="Full" version="2">
  <description>all kinds</description>
  <material name="rubber"><mu>0.9</mu><bounce>0.1</bounce></material>
  <body type="Box" name="Base">
    <mass>10</mass>
    <size><x>0.6</x><y>0.2</y><z>0.3</z></size>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.5</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <body type="Cylinder" name="Wheel" material="rubber">
    <mass>2</mass><radius>0.2</radius><length>0.1</length>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.2</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0.25</T23>
    </transformation>
  </body>
  <body type="Box" name="Carriage">
    <mass>1</mass><size><x>0.1</x><y>0.1</y><z>0.1</z></size>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0.4</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.5</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <body type="Sphere" name="Head"><mass>1.5</mass><radius>0.1</radius>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.8</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <body type="Capsule" name="Arm"><mass>0.8</mass><radius>0.03</radius><length>0.3</length>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.5</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>-0.4</T23>
    </transformation>
  </body>
  <body type="Body" name="Tip"><mass>0.5</mass>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.5</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>-0.6</T23>
    </transformation>
  </body>
  <body type="Box" name="Plate"><mass>0.7</mass><size><x>0.2</x><y>0.01</y><z>0.2</z></size>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.61</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <joint type="Hinge" name="Axle">
    <body1>Base</body1><body2>Wheel</body2>
    <anchor><x>0</x><y>0.2</y><z>0.25</z></anchor>
    <axis1><x>0</x><y>0</y><z>2</z></axis1>
  </joint>
  <joint type="Slider" name="Rail">
    <body1>Carriage</body1><body2>Base</body2>
    <axis1><x>1</x><y>0</y><z>0</z></axis1>
    <limits><lo>-0.1</lo><hi>5</hi></limits>
  </joint>
  <joint type="Ball" name="Neck">
    <body1>Head</body1><body2>Base</body2>
    <anchor><x>0</x><y>0.7</y><z>0</z></anchor>
  </joint>
  <joint type="Universal" name="Shoulder">
    <body1>Arm</body1><body2>Base</body2>
    <anchor><x>0</x><y>0.5</y><z>-0.15</z></anchor>
    <axis1><x>1</x><y>0</y><z>0</z></axis1>
    <axis2><x>0</x><y>1</y><z>0</z></axis2>
    <limits axis="2"><lo>-0.5</lo><hi>0.5</hi></limits>
  </joint>
  <joint type="Hinge2" name="Wrist">
    <body1>Tip</body1><body2>Arm</body2>
    <anchor><x>0</x><y>0.5</y><z>-0.55</z></anchor>
    <axis1><x>0</x><y>1</y><z>0</z></axis1>
    <axis2><x>0</x><y>0</y><z>1</z></axis2>
  </joint>
  <joint type="Fixed" name="Mount">
    <body1>Plate</body1><body2>Base</body2>
  </joint>
  <sensor type="Echo" name="Echo" port="1025"><bodyRef>Base</bodyRef></sensor>
  <sensor type="Position" name="Where" port="1026">
    <bodyRef>Head</bodyRef>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.1</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
    <rate>50</rate>
  </sensor>
  <sensor type="Scanner" name="Laser" port="1027">
    <bodyRef>Head</bodyRef>
    <parameter name="rays">21</parameter>
    <parameter name="halfSpan">0.2</parameter>
    <parameter name="range">8</parameter>
  </sensor>
  <sensor type="Velocity" name="Speed"><bodyRef>Wheel</bodyRef></sensor>
  <sensor type="ForceTorque" name="AxleLoad"><jointRef>Axle</jointRef></sensor>
  <actuator type="JointController" name="AxleMotor" port="1028"><jointRef>Axle</jointRef></actuator>
  <actuator type="LinearMotor" name="RailMotor" port="1029"><jointRef>Rail</jointRef></actuator>
  <actuator type="AngleController" name="ShoulderMotor" port="1030"><jointRef>Shoulder</jointRef></actuator>
  <actuator type="JointController" name="RailSpeed"><jointRef>Rail</jointRef></actuator>
</robot>
)";

TEST(LoaderRobot, EveryJointKind) {
  const RobotLoadResult result = ParseRobot(kFullRobot, "full.xml");
  ASSERT_TRUE(result.robot) << result.diagnostics.Format();
  const Robot& r = *result.robot;
  EXPECT_EQ(r.model_name, "Full");
  EXPECT_EQ(r.description, "all kinds");
  EXPECT_EQ(r.file, "full.xml");
  ASSERT_EQ(r.joints.size(), 6u);
  const double inf = std::numeric_limits<double>::infinity();

  const Joint* axle = r.FindJoint("Axle");
  ASSERT_NE(axle, nullptr);
  EXPECT_EQ(axle->kind, JointKind::kHinge);
  EXPECT_EQ(axle->body1, "Base");
  EXPECT_EQ(axle->body2, "Wheel");
  EXPECT_EQ(axle->anchor, Eigen::Vector3d(0, 0.2, 0.25));
  EXPECT_TRUE(axle->axis[0].isApprox(Eigen::Vector3d(0, 0, 1), kTight));  // (0, 0, 2) normalised
  EXPECT_EQ(axle->lo_stop[0], -inf);  // no limits: free
  EXPECT_EQ(axle->hi_stop[0], inf);
  EXPECT_EQ(axle->where.line, LineOf(kFullRobot, "name=\"Axle\""));

  // Slider limits are metres, not bound to [-pi, pi].
  const Joint* rail = r.FindJoint("Rail");
  ASSERT_NE(rail, nullptr);
  EXPECT_EQ(rail->kind, JointKind::kSlider);
  EXPECT_EQ(rail->lo_stop[0], -0.1);
  EXPECT_EQ(rail->hi_stop[0], 5.0);

  const Joint* neck = r.FindJoint("Neck");
  ASSERT_NE(neck, nullptr);
  EXPECT_EQ(neck->kind, JointKind::kBall);
  EXPECT_EQ(neck->anchor, Eigen::Vector3d(0, 0.7, 0));

  const Joint* shoulder = r.FindJoint("Shoulder");
  ASSERT_NE(shoulder, nullptr);
  EXPECT_EQ(shoulder->kind, JointKind::kUniversal);
  EXPECT_EQ(shoulder->axis[0], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(shoulder->axis[1], Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(shoulder->lo_stop[0], -inf);
  EXPECT_EQ(shoulder->lo_stop[1], -0.5);
  EXPECT_EQ(shoulder->hi_stop[1], 0.5);

  const Joint* wrist = r.FindJoint("Wrist");
  ASSERT_NE(wrist, nullptr);
  EXPECT_EQ(wrist->kind, JointKind::kHinge2);
  EXPECT_EQ(wrist->axis[1], Eigen::Vector3d(0, 0, 1));

  const Joint* mount = r.FindJoint("Mount");
  ASSERT_NE(mount, nullptr);
  EXPECT_EQ(mount->kind, JointKind::kFixed);
  EXPECT_EQ(mount->body1, "Plate");
}

TEST(LoaderRobot, BodiesMaterialsAndMass) {
  const RobotLoadResult result = ParseRobot(kFullRobot, "full.xml");
  ASSERT_TRUE(result.robot) << result.diagnostics.Format();
  const Robot& r = *result.robot;
  ASSERT_EQ(r.bodies.size(), 7u);
  // 10 + 2 + 1 + 1.5 + 0.8 + 0.5 + 0.7
  EXPECT_NEAR(r.TotalMass(), 16.5, kTight);
  const Body* wheel = r.FindBody("Wheel");
  ASSERT_NE(wheel, nullptr);
  EXPECT_EQ(wheel->material, "rubber");
  EXPECT_EQ(wheel->geometry.kind, GeometryKind::kCylinder);
  EXPECT_EQ(wheel->pose.translation(), Eigen::Vector3d(0, 0.2, 0.25));
  EXPECT_EQ(r.FindBody("Base")->material, "");  // the default material
  EXPECT_EQ(r.FindBody("Tip")->geometry.kind, GeometryKind::kNone);
  EXPECT_EQ(r.FindBody("Arm")->geometry.kind, GeometryKind::kCapsule);
  ASSERT_EQ(r.materials.size(), 1u);
  EXPECT_EQ(r.materials[0].name, "rubber");
  EXPECT_EQ(r.materials[0].mu, 0.9);
  EXPECT_EQ(r.materials[0].bounce, 0.1);
}

TEST(LoaderRobot, EverySensorKind) {
  const RobotLoadResult result = ParseRobot(kFullRobot, "full.xml");
  ASSERT_TRUE(result.robot) << result.diagnostics.Format();
  const std::vector<Sensor>& s = result.robot->sensors;
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0].name, "Echo");
  EXPECT_EQ(s[0].kind, SensorKind::kEcho);
  EXPECT_EQ(s[0].body, "Base");
  EXPECT_EQ(s[0].port, 1025);
  EXPECT_EQ(s[0].rate, 0.0);  // on request

  EXPECT_EQ(s[1].kind, SensorKind::kPosition);
  EXPECT_EQ(s[1].body, "Head");
  EXPECT_EQ(s[1].port, 1026);
  EXPECT_EQ(s[1].rate, 50.0);
  EXPECT_EQ(s[1].mount.translation(), Eigen::Vector3d(0, 0.1, 0));

  EXPECT_EQ(s[2].kind, SensorKind::kScanner);
  EXPECT_EQ(s[2].rays, 21);
  EXPECT_EQ(s[2].half_span, 0.2);
  EXPECT_EQ(s[2].range, 8.0);
  EXPECT_EQ(s[2].port, 1027);

  EXPECT_EQ(s[3].kind, SensorKind::kVelocity);
  EXPECT_EQ(s[3].body, "Wheel");
  EXPECT_EQ(s[3].port, 0);  // no legacy port

  // A force/torque sensor measures its joint, on the joint's body2.
  EXPECT_EQ(s[4].kind, SensorKind::kForceTorque);
  EXPECT_EQ(s[4].joint, "Axle");
  EXPECT_EQ(s[4].body, "Wheel");
  EXPECT_EQ(s[4].where.line, LineOf(kFullRobot, "name=\"AxleLoad\""));
}

TEST(LoaderRobot, EveryActuatorKind) {
  const RobotLoadResult result = ParseRobot(kFullRobot, "full.xml");
  ASSERT_TRUE(result.robot) << result.diagnostics.Format();
  const std::vector<Actuator>& a = result.robot->actuators;
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0].kind, ActuatorKind::kJointVelocity);
  EXPECT_EQ(a[0].joint, "Axle");
  EXPECT_EQ(a[0].port, 1028);
  EXPECT_EQ(a[1].kind, ActuatorKind::kLinearMotor);
  EXPECT_EQ(a[1].joint, "Rail");
  EXPECT_EQ(a[2].kind, ActuatorKind::kAngle);
  EXPECT_EQ(a[2].joint, "Shoulder");
  EXPECT_EQ(a[2].port, 1030);
  // A velocity controller may drive a slider too.
  EXPECT_EQ(a[3].kind, ActuatorKind::kJointVelocity);
  EXPECT_EQ(a[3].joint, "Rail");
  EXPECT_EQ(a[3].port, 0);
}

// ------------------------------------------------------------ robots in worlds

TEST(LoaderWorld, PlacesRobotsRelativeToTheWorldFile) {
  MemoryFiles disk;
  disk.files["/sims/robots/full.xml"] = kFullRobot;
  disk.files["/elsewhere/full.xml"] = kFullRobot;
  const std::string xml = R"(<world>
  <material name="rubber"><mu>0.4</mu></material>
  <robot name="Left" file="../robots/full.xml">
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>-2</T23>
    </transformation>
  </robot>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "/sims/worlds/two.xml", disk.Reader());
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  ASSERT_EQ(result.world->robots.size(), 1u);
  const RobotInstance& left = result.world->robots[0];
  EXPECT_EQ(left.name, "Left");
  EXPECT_EQ(left.file, "../robots/full.xml");
  EXPECT_EQ(left.resolved_file, "/sims/robots/full.xml");
  EXPECT_EQ(left.placement.translation(), Eigen::Vector3d(0, 0, -2));
  EXPECT_EQ(left.robot.model_name, "Full");
  EXPECT_EQ(left.where.line, LineOf(xml, "name=\"Left\""));
  // Both define "rubber": the world's wins.
  ASSERT_NE(result.world->FindMaterial("rubber"), nullptr);
  EXPECT_EQ(result.world->FindMaterial("rubber")->mu, 0.4);

  const std::string absolute =
      R"(<world><robot name="Far" file="/elsewhere/full.xml"/></world>)";
  const WorldLoadResult far = ParseWorld(absolute, "/sims/worlds/far.xml", disk.Reader());
  ASSERT_TRUE(far.world) << far.diagnostics.Format();
  EXPECT_EQ(far.world->robots.at(0).resolved_file, "/elsewhere/full.xml");
}

TEST(LoaderWorld, RobotMaterialsJoinTheWorld) {
  MemoryFiles disk;
  disk.files["w/full.xml"] = kFullRobot;
  const WorldLoadResult result =
      ParseWorld(R"(<world><robot name="R" file="full.xml"/></world>)", "w/world.xml",
                 disk.Reader());
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  ASSERT_NE(result.world->FindMaterial("rubber"), nullptr);
  EXPECT_EQ(result.world->FindMaterial("rubber")->mu, 0.9);
}

TEST(LoaderWorld, SummaryPerRobot) {
  MemoryFiles disk;
  disk.files["w/full.xml"] = kFullRobot;
  const WorldLoadResult result = ParseWorld(
      R"(<world name="Sum"><robot name="R" file="full.xml"/></world>)", "w/world.xml",
      disk.Reader());
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  const std::string summary = DescribeWorld(*result.world);
  EXPECT_NE(summary.find("world 'Sum'"), std::string::npos) << summary;
  EXPECT_NE(summary.find("robot 'R' = Full"), std::string::npos) << summary;
  EXPECT_NE(summary.find("bodies: 7, joints: 6, sensors: 5, actuators: 4, total mass: 16.500 kg"),
            std::string::npos)
      << summary;
}

// ------------------------------------------------------------ diagnostics

// A file with three unrelated problems reports all three, each at its own
// element, and nothing more.
TEST(LoaderDiagnostics, EveryProblemOfARobotFile) {
  const std::string xml = R"(<robot name="Three">
  <body type="Box" name="A">
    <mass>-1</mass>
    <size><x>1</x><y>1</y><z>1</z></size>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <body type="Sphere" name="B"><mass>1</mass><radius>0.1</radius>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>1</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <body type="Sphere" name="Loose"><mass>1</mass><radius>0.1</radius>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>2</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
  </body>
  <joint type="Fixed" name="AB"><body1>A</body1><body2>B</body2></joint>
  <sensor type="Echo" name="Echo" port="80"><bodyRef>A</bodyRef></sensor>
</robot>)";
  const RobotLoadResult result = ParseRobot(xml, "three.xml");
  EXPECT_FALSE(result.robot);
  ASSERT_EQ(result.diagnostics.size(), 3u) << result.diagnostics.Format();

  const Diagnostic* mass = Find(result.diagnostics, "mass");
  ASSERT_NE(mass, nullptr) << result.diagnostics.Format();
  EXPECT_EQ(mass->file, "three.xml");
  EXPECT_EQ(mass->line, LineOf(xml, "<mass>-1</mass>"));
  EXPECT_NE(mass->message.find("'A'"), std::string::npos) << mass->message;
  EXPECT_NE(mass->message.find("-1"), std::string::npos) << mass->message;

  const Diagnostic* port = Find(result.diagnostics, "sensor");
  ASSERT_NE(port, nullptr) << result.diagnostics.Format();
  EXPECT_EQ(port->line, LineOf(xml, "port=\"80\""));
  EXPECT_NE(port->message.find("port 80"), std::string::npos) << port->message;

  const Diagnostic* loose = Find(result.diagnostics, "body");
  ASSERT_NE(loose, nullptr) << result.diagnostics.Format();
  EXPECT_EQ(loose->line, LineOf(xml, "name=\"Loose\""));
  EXPECT_NE(loose->message.find("'Loose'"), std::string::npos) << loose->message;
}

TEST(LoaderDiagnostics, NonFiniteNumberAtItsElement) {
  const std::string xml = "<world><object type=\"Body\" name=\"P\"><mass>1</mass>\n"
      "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>\n"
      "<T10>0</T10><T11>1</T11><T12>0</T12><T13>1e400</T13>\n"
      "<T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></object></world>";
  const WorldLoadResult result = ParseWorld(xml, "nan.xml");
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.element, "T13");
  EXPECT_EQ(d.line, 3);
  EXPECT_NE(d.message.find("'1e400'"), std::string::npos) << d.message;
}

// A joint that fails its own check is not reported again by the actuator
// and the force sensor that refer to it.
TEST(LoaderDiagnostics, NoSecondErrorForReferencesToABrokenJoint) {
  std::string xml = kFullRobot;
  const std::string good = "<axis1><x>0</x><y>0</y><z>2</z></axis1>";
  xml.replace(xml.find(good), good.size(), "<axis1><x>0</x><y>0</y><z>0</z></axis1>");
  const RobotLoadResult result = ParseRobot(xml, "full.xml");
  EXPECT_FALSE(result.robot);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].element, "axis1");
  EXPECT_EQ(result.diagnostics.items()[0].line,
            LineOf(xml, "<axis1><x>0</x><y>0</y><z>0</z></axis1>"));
}

TEST(LoaderDiagnostics, ActuatorThatCannotDriveItsJoint) {
  std::string xml = kFullRobot;
  const std::string good = R"(name="ShoulderMotor" port="1030"><jointRef>Shoulder<)";
  xml.replace(xml.find(good), good.size(), R"(name="ShoulderMotor" port="1030"><jointRef>Mount<)");
  const RobotLoadResult result = ParseRobot(xml, "full.xml");
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.element, "jointRef");
  EXPECT_EQ(d.line, LineOf(xml, "name=\"ShoulderMotor\""));
  EXPECT_NE(d.message.find("Fixed joint 'Mount'"), std::string::npos) << d.message;
}

TEST(LoaderDiagnostics, RobotProblemsPointIntoTheRobotFile) {
  std::string robot = kFullRobot;
  const std::string good = R"(<body type="Box" name="Base">)";
  robot.replace(robot.find(good), good.size(), R"(<body type="Box" name="Base" material="felt">)");
  MemoryFiles disk;
  disk.files["w/full.xml"] = robot;
  const std::string xml = "<world>\n  <robot name=\"R\" file=\"full.xml\"/>\n</world>";
  const WorldLoadResult result = ParseWorld(xml, "w/world.xml", disk.Reader());
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.file, "w/full.xml");
  EXPECT_EQ(d.line, LineOf(robot, "material=\"felt\""));
  EXPECT_EQ(d.element, "body");
  EXPECT_NE(d.message.find("'felt'"), std::string::npos) << d.message;
}

TEST(LoaderDiagnostics, UnreadableRobotFile) {
  MemoryFiles disk;  // empty
  const std::string xml = "<world>\n\n  <robot name=\"R\" file=\"gone.xml\"/>\n</world>";
  const WorldLoadResult result = ParseWorld(xml, "w/world.xml", disk.Reader());
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 2u) << result.diagnostics.Format();
  const Diagnostic& placing = result.diagnostics.items()[0];
  EXPECT_EQ(placing.file, "w/world.xml");
  EXPECT_EQ(placing.line, 3);
  EXPECT_EQ(placing.element, "robot");
  EXPECT_NE(placing.message.find("'gone.xml'"), std::string::npos) << placing.message;
  const Diagnostic& missing = result.diagnostics.items()[1];
  EXPECT_EQ(missing.file, "w/gone.xml");
  EXPECT_EQ(missing.line, 0);
}

TEST(LoaderDiagnostics, PortClashBetweenRobotsIsTheWorlds) {
  MemoryFiles disk;
  disk.files["w/full.xml"] = kFullRobot;
  const std::string xml = R"(<world>
  <robot name="One" file="full.xml"/>
  <robot name="Two" file="full.xml"/>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "w/world.xml", disk.Reader());
  EXPECT_FALSE(result.world);
  // Ports 1025..1030: six clashes, all at the second placement.
  ASSERT_EQ(result.diagnostics.size(), 6u) << result.diagnostics.Format();
  for (const Diagnostic& d : result.diagnostics.items()) {
    EXPECT_EQ(d.file, "w/world.xml");
    EXPECT_EQ(d.line, LineOf(xml, "name=\"Two\""));
    EXPECT_EQ(d.element, "robot");
    EXPECT_NE(d.message.find("'One/"), std::string::npos) << d.message;
  }
  EXPECT_NE(result.diagnostics.items()[0].message.find("port 1025"), std::string::npos);
}

TEST(LoaderDiagnostics, BadHeightfieldSampleAtItsOwnLine) {
  const std::string xml = R"(<world>
  <heightfield rows="3" columns="2">
    <width>1</width><depth>1</depth>
    <samples>
      1 2
      <!-- the middle row -->
      3 x4
      5 6
    </samples>
  </heightfield>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "field.xml");
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.element, "samples");
  EXPECT_EQ(d.line, LineOf(xml, "3 x4"));
  EXPECT_NE(d.message.find("sample 4 (row 2, column 2) 'x4'"), std::string::npos) << d.message;
}

// libxml2's guesses after the first fatal error are not passed on.
TEST(LoaderDiagnostics, NotWellFormedIsOneProblem) {
  const std::string xml = "<world>\n  <object type=\"Sphere\" name=Ball>\n    <mass>1</mass>\n"
                          "  </object>\n</world>\n";
  const WorldLoadResult result = ParseWorld(xml, "bad.xml");
  EXPECT_FALSE(result.world);
  ASSERT_FALSE(result.diagnostics.empty());
  for (const Diagnostic& d : result.diagnostics.items()) {
    EXPECT_EQ(d.file, "bad.xml");
    EXPECT_EQ(d.line, 2) << d.Format();
    EXPECT_EQ(d.message.find('\n'), std::string::npos) << d.message;
  }
}

TEST(LoaderDiagnostics, OwnDeclarationsAreRefusedAtTheirLine) {
  const std::string xml = "<?xml version=\"1.0\"?>\n\n<!DOCTYPE world [\n"
                          "  <!ATTLIST object extra CDATA #IMPLIED>\n]>\n<world/>\n";
  const WorldLoadResult result = ParseWorld(xml, "own.xml");
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].element, "DOCTYPE");
  EXPECT_EQ(result.diagnostics.items()[0].line, 3);
}

TEST(LoaderDiagnostics, DtdErrorsNameTheElement) {
  const std::string xml = R"(<world>
  <gravity><x>0</x><y>-9.81</y></gravity>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "dtd.xml");
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].element, "gravity");
  EXPECT_EQ(result.diagnostics.items()[0].line, 2);
}

TEST(LoaderDiagnostics, ThrowingFormCarriesEveryDiagnostic) {
  const std::string path = std::string(SP_SOURCE_DIR) + "/tests/models/broken/physics_zero_mass.xml";
  try {
    LoadWorldOrThrow(path);
    FAIL() << "no ModelError for " << path;
  } catch (const ModelError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
    EXPECT_EQ(e.diagnostics().items()[0].file, path);
    EXPECT_EQ(e.diagnostics().items()[0].element, "mass");
    EXPECT_EQ(std::string(e.what()), e.diagnostics().Format());
  }
}

}  // namespace
}  // namespace simpartner::model
