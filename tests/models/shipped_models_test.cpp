// The shipped worlds and WorkPartner robots (models/worlds, models/robots)
// against the numbers of SPEC 7 and 8 and the conventions of
// models/README.md. The expected numbers are written here as literals, never
// computed from the files under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "simpartner/model/loader.h"
#include "simpartner/model/sensor_parameters.h"

namespace simpartner::model {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(SP_SOURCE_DIR) / "models";

// ---------------------------------------------------------------- SPEC numbers
constexpr double kAxleX = 0.6;          // SPEC 7: Turner joint to each axle
constexpr double kHalfTrack = 0.3;      // SPEC 7: track width 0.6
constexpr double kWheelRadius = 0.235;  // SPEC 7
constexpr double kGen3Mass = 202.0;     // SPEC 7
constexpr double kSupportTorsoMass = 51.0;  // SPEC 7: front support + torso
constexpr double kGen1LightMass = 18.0;     // SPEC 7
// SPEC 8: real static wheel loads [N], wheels 1..4.
constexpr double kW1 = 579.15, kW2 = 774.90, kW3 = 669.12, kW4 = 676.03;
constexpr double kGen4Mass = 275.15;    // (W1 + W2 + W3 + W4) / 9.81, rounded
constexpr double kScannerAhead = 0.665; // SPEC 8: wall 6 m from the centre, 5.335 from the scanner
constexpr int kScannerRays = 11;        // SPEC 4
constexpr double kScannerHalfSpan = 0.1;
constexpr double kScannerRange = 10.0;
// gen4's supports, our design (models/README.md, workpartner_gen4.xml):
// tyres of 2e5 N/m and 7000 N s/m per wheel, which on flat ground touch at
// two contact points (the wheel's faces) of half that each; legs 2 and 4
// 0.5235 mm longer than legs 1 and 3 (their whole leg sits that much lower).
constexpr double kGen4TyreStiffness = 2e5;    // [N/m] per wheel
constexpr double kGen4TyreDamping = 7000.0;   // [N s/m] per wheel
constexpr double kGen4LegOffset = 0.0005235;  // [m]
// The run parameters the joints' softness is per step for (parameters.txt)
// and the hold of SPEC 4 (sim_core/controllers.h: velocity kHoldGain * error).
constexpr double kStep = 0.001;                       // [s] stepsize
constexpr double kGlobalERP = 0.2, kGlobalCFM = 1e-5;  // joints
constexpr double kDefaultSoftERP = 0.2;                // contactSoftERP: a ground without material
constexpr double kDefaultSoftCFM = 1e-5;               // contactSoftCFM
constexpr double kHoldGain = 20.0;                     // [1/s]
constexpr double kMaxCorrectingVel = 0.2;              // [m/s] contactMaxCorrectingVel
// Our design (models/README.md): gen1 = chassis 20 + 32 kg + four 21 kg legs.
constexpr double kGen1Mass = 136.0;
constexpr double kGen2Mass = 187.0;     // gen1 + 51

// Wheel numbering (SPEC 7): 1 front right, 2 front left, 3 rear left,
// 4 rear right; robot frame x forward, y up, z right.
struct WheelPlace {
  int number;
  double x, z;
};
const WheelPlace kWheels[] = {{1, +kAxleX, +kHalfTrack},
                              {2, +kAxleX, -kHalfTrack},
                              {3, -kAxleX, -kHalfTrack},
                              {4, -kAxleX, +kHalfTrack}};

const char* const kGenerations[] = {"gen1", "gen1_light", "gen2", "gen3", "gen4"};

// How much lower than SPEC 7's place a leg (and its wheel) sits: gen4's
// legs 2 and 4 are kGen4LegOffset longer, which makes its cross weight.
double LegDrop(const std::string& gen, int wheel) {
  return gen == "gen4" && (wheel == 2 || wheel == 4) ? kGen4LegOffset : 0.0;
}

Robot LoadShippedRobot(const std::string& gen) {
  const std::string path = (kModels / "robots" / ("workpartner_" + gen + ".xml")).string();
  RobotLoadResult result = LoadRobotFile(path);
  EXPECT_TRUE(result.diagnostics.empty()) << result.diagnostics.Format();
  if (!result.robot) {
    ADD_FAILURE() << "cannot load " << path;
    return Robot{};
  }
  return std::move(*result.robot);
}

const Robot& Shipped(const std::string& gen) {
  static std::map<std::string, Robot> cache;
  auto it = cache.find(gen);
  if (it == cache.end()) it = cache.emplace(gen, LoadShippedRobot(gen)).first;
  return it->second;
}

const Sensor* FindSensor(const Robot& robot, const std::string& name) {
  for (const Sensor& s : robot.sensors)
    if (s.name == name) return &s;
  return nullptr;
}

const Actuator* FindActuator(const Robot& robot, const std::string& name) {
  for (const Actuator& a : robot.actuators)
    if (a.name == name) return &a;
  return nullptr;
}

template <class A, class B>
bool Near(const A& a, const B& b, double tolerance) {
  return (a - b).cwiseAbs().maxCoeff() <= tolerance;
}

// Centre of mass of the robot in its frame.
Eigen::Vector3d CentreOfMass(const Robot& robot) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Body& b : robot.bodies) sum += b.mass * (b.pose * b.com);
  return sum / robot.TotalMass();
}

// Axis-aligned bounding box of a body's shape in the robot frame.
struct Box3 {
  Eigen::Vector3d lo, hi;
};
Box3 Bounds(const Body& body) {
  const Eigen::Matrix3d r = body.pose.linear();
  const Eigen::Vector3d centre = body.pose.translation();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
  const Eigen::Vector3d& s = body.geometry.size;
  switch (body.geometry.kind) {
    case GeometryKind::kBox:
      half = r.cwiseAbs() * (s / 2.0);
      break;
    case GeometryKind::kSphere:
      half.setConstant(s.x());
      break;
    case GeometryKind::kCylinder:
    case GeometryKind::kCapsule: {
      const Eigen::Vector3d axis = r.col(2);
      const double cap = body.geometry.kind == GeometryKind::kCapsule ? s.x() : 0.0;
      for (int i = 0; i < 3; ++i)
        half[i] = std::abs(axis[i]) * (s.y() / 2.0 + cap) +
                  s.x() * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i]));
      break;
    }
    case GeometryKind::kNone:
      break;
  }
  return Box3{centre - half, centre + half};
}

// ============================================================== worlds

std::vector<fs::path> ShippedWorlds() {
  std::vector<fs::path> worlds;
  for (const auto& entry : fs::directory_iterator(kModels / "worlds"))
    if (entry.is_regular_file() && entry.path().extension() == ".xml")
      worlds.push_back(entry.path());
  std::sort(worlds.begin(), worlds.end());
  return worlds;
}

TEST(ShippedWorlds, EveryWorldLoadsWithoutDiagnostics) {
  const std::vector<fs::path> worlds = ShippedWorlds();
  ASSERT_FALSE(worlds.empty());
  for (const fs::path& path : worlds) {
    SCOPED_TRACE(path.string());
    const WorldLoadResult result = LoadWorldFile(path.string());
    EXPECT_TRUE(result.diagnostics.empty()) << result.diagnostics.Format();
    EXPECT_TRUE(result.world.has_value());
    if (result.world) {
      EXPECT_FALSE(result.world->description.empty());
    }
  }
}

TEST(ShippedWorlds, TheDocumentedWorldsExist) {
  std::set<std::string> names;
  for (const fs::path& path : ShippedWorlds()) names.insert(path.filename().string());
  for (const char* required :
       {"flat_ground.xml", "flat_ground_gen2.xml", "gen1_flat.xml", "gen4_flat.xml", "maze.xml",
        "scanner_wall.xml", "pole_task.xml", "slippery_ground.xml", "free_fall.xml",
        "free_fall_thrown.xml", "free_fall_g50.xml", "sliding_cube.xml", "two_spheres.xml",
        "test_track.xml"})
    EXPECT_EQ(names.count(required), 1u) << required;
}

World LoadShippedWorld(const std::string& name) {
  WorldLoadResult result = LoadWorldFile((kModels / "worlds" / name).string());
  EXPECT_TRUE(result.world.has_value()) << result.diagnostics.Format();
  if (!result.world) return World{};
  return std::move(*result.world);
}

const Body* FindObject(const World& world, const std::string& name) {
  for (const Body& b : world.objects)
    if (b.name == name) return &b;
  return nullptr;
}

// The y-up convention and which robot each world places.
TEST(ShippedWorlds, RobotWorldsAreYUpWithTheRightGeneration) {
  const std::map<std::string, std::string> robot_of = {
      {"flat_ground.xml", "WorkPartner gen3"},   {"flat_ground_gen2.xml", "WorkPartner gen2"},
      {"gen1_flat.xml", "WorkPartner gen1"},     {"gen4_flat.xml", "WorkPartner gen4"},
      {"maze.xml", "WorkPartner gen2"},          {"scanner_wall.xml", "WorkPartner gen2"},
      {"pole_task.xml", "WorkPartner gen3"},     {"slippery_ground.xml", "WorkPartner gen1 light"},
      {"test_track.xml", "WorkPartner gen4"}};
  for (const auto& [file, model_name] : robot_of) {
    SCOPED_TRACE(file);
    const World world = LoadShippedWorld(file);
    EXPECT_TRUE(Near(world.gravity, Eigen::Vector3d(0, -9.81, 0), 1e-12));
    EXPECT_EQ(world.collision_space, CollisionSpaceKind::kHash);
    ASSERT_EQ(world.robots.size(), 1u);
    EXPECT_EQ(world.robots[0].robot.model_name, model_name);
    // Upright, at ground level (y = 0 plane or the flat start of the track).
    EXPECT_TRUE(world.robots[0].placement.linear().isIdentity(1e-12));
    EXPECT_NEAR(world.robots[0].placement.translation().y(), 0.0, 1e-12);
    if (file == "test_track.xml") continue;
    ASSERT_TRUE(world.has_plane);
    EXPECT_TRUE(Near(world.plane, Eigen::Vector4d(0, 1, 0, 0), 1e-12));
  }
}

TEST(ShippedWorlds, ExperimentWorldsMatchTheSpec) {
  {  // free fall from 500 m (SPEC 8), the original's TestParticle
    const World w = LoadShippedWorld("free_fall.xml");
    const Body* p = FindObject(w, "TestParticle");
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(p->geometry.kind, GeometryKind::kNone);
    EXPECT_DOUBLE_EQ(p->mass, 1.0);
    EXPECT_DOUBLE_EQ(p->pose.translation().y(), 500.0);
    EXPECT_TRUE(p->linear_velocity.isZero());
    EXPECT_FALSE(w.has_plane);
  }
  {
    const World w = LoadShippedWorld("free_fall_thrown.xml");
    const Body* p = FindObject(w, "TestParticle");
    ASSERT_NE(p, nullptr);
    EXPECT_TRUE(Near(p->linear_velocity, Eigen::Vector3d(10, 10, 0), 1e-12));
  }
  {
    const World w = LoadShippedWorld("free_fall_g50.xml");
    EXPECT_TRUE(Near(w.gravity, Eigen::Vector3d(0, -50, 0), 1e-12));
  }
  {  // 1 m, 1 kg cube at 10 m/s on the ground
    const World w = LoadShippedWorld("sliding_cube.xml");
    const Body* c = FindObject(w, "Cube");
    ASSERT_NE(c, nullptr);
    EXPECT_DOUBLE_EQ(c->mass, 1.0);
    EXPECT_TRUE(Near(c->geometry.size, Eigen::Vector3d(1, 1, 1), 1e-12));
    EXPECT_DOUBLE_EQ(c->pose.translation().y(), 0.5);
    EXPECT_TRUE(Near(c->linear_velocity, Eigen::Vector3d(10, 0, 0), 1e-12));
    const Material* floor = w.FindMaterial(w.plane_material);
    const Material* cube = w.FindMaterial(c->material);
    ASSERT_NE(floor, nullptr);
    ASSERT_NE(cube, nullptr);
    EXPECT_DOUBLE_EQ(std::min(floor->mu, cube->mu), 0.5);
  }
  {  // two spheres r 0.5 with equal and opposite velocities, mirror images
    const World w = LoadShippedWorld("two_spheres.xml");
    ASSERT_EQ(w.objects.size(), 2u);
    const Body& a = w.objects[0];
    const Body& b = w.objects[1];
    EXPECT_DOUBLE_EQ(a.geometry.size.x(), 0.5);
    EXPECT_DOUBLE_EQ(b.geometry.size.x(), 0.5);
    EXPECT_DOUBLE_EQ(a.mass, b.mass);
    EXPECT_TRUE(Near(a.linear_velocity, -b.linear_velocity, 1e-12));
    EXPECT_NE(a.linear_velocity.x(), 0.0);
    EXPECT_DOUBLE_EQ(a.pose.translation().x(), -b.pose.translation().x());
    EXPECT_DOUBLE_EQ(a.pose.translation().y(), b.pose.translation().y());
    EXPECT_TRUE(w.gravity.isZero());
  }
  {  // 18 kg gen1 on mu 0.025, rubber wheels mu 1
    const World w = LoadShippedWorld("slippery_ground.xml");
    const Material* ground = w.FindMaterial(w.plane_material);
    ASSERT_NE(ground, nullptr);
    EXPECT_DOUBLE_EQ(ground->mu, 0.025);
    const Body* wheel = w.robots.at(0).robot.FindBody("Wheel1");
    ASSERT_NE(wheel, nullptr);
    const Material* rubber = w.FindMaterial(wheel->material);
    ASSERT_NE(rubber, nullptr);
    EXPECT_DOUBLE_EQ(rubber->mu, 1.0);
  }
  {  // a static wall whose near face is 6 m ahead of the robot centre, across x
    const World w = LoadShippedWorld("scanner_wall.xml");
    const Body* wall = FindObject(w, "Wall");
    ASSERT_NE(wall, nullptr);
    EXPECT_TRUE(wall->is_static);
    EXPECT_TRUE(wall->pose.linear().isIdentity(1e-12));
    EXPECT_NEAR(wall->pose.translation().x() - wall->geometry.size.x() / 2.0, 6.0, 1e-12);
    EXPECT_NEAR(w.robots.at(0).placement.translation().x(), 0.0, 1e-12);
  }
  {  // seven boxes and one cylinder
    const World w = LoadShippedWorld("maze.xml");
    int boxes = 0, cylinders = 0;
    for (const Body& b : w.objects) {
      boxes += b.geometry.kind == GeometryKind::kBox;
      cylinders += b.geometry.kind == GeometryKind::kCylinder;
    }
    EXPECT_EQ(boxes, 7);
    EXPECT_EQ(cylinders, 1);
  }
  {  // a 5 kg pole across two cubes, two more cubes
    const World w = LoadShippedWorld("pole_task.xml");
    const Body* pole = FindObject(w, "Pole");
    ASSERT_NE(pole, nullptr);
    EXPECT_DOUBLE_EQ(pole->mass, 5.0);
    EXPECT_FALSE(pole->is_static);
    int cubes = 0;
    for (const Body& b : w.objects) {
      if (b.geometry.kind != GeometryKind::kBox) continue;
      const Eigen::Vector3d s = b.geometry.size;
      EXPECT_DOUBLE_EQ(s.x(), s.y()) << b.name;
      EXPECT_DOUBLE_EQ(s.x(), s.z()) << b.name;
      ++cubes;
    }
    EXPECT_EQ(cubes, 4);
  }
  {  // the heightfield track: rows along z, columns along x, ~40 m from x = 0
    const World w = LoadShippedWorld("test_track.xml");
    ASSERT_TRUE(w.heightfield.has_value());
    const Heightfield& h = *w.heightfield;
    const double x_min = h.position.x() - h.width / 2.0;
    const double x_max = h.position.x() + h.width / 2.0;
    EXPECT_LT(x_min, -1.0);
    EXPECT_GE(x_max, 40.0);
    // Level start under the robot, lower after the slope before 20 m.
    for (double x : {-0.6, 0.0, 0.6})
      for (double z : {-0.3, 0.3}) EXPECT_NEAR(h.HeightAt(x - h.position.x(), z), 0.0, 1e-9);
    EXPECT_LT(h.HeightAt(20.0 - h.position.x(), 0.0), h.HeightAt(15.0 - h.position.x(), 0.0) - 0.3);
    EXPECT_NE(FindObject(w, "Plank1"), nullptr);
    EXPECT_NE(FindObject(w, "Plank2"), nullptr);
  }
}

// ============================================================== robots

TEST(ShippedRobots, TotalMassesFollowTheSpec) {
  EXPECT_NEAR(Shipped("gen3").TotalMass(), kGen3Mass, 1e-6);
  EXPECT_NEAR(Shipped("gen1_light").TotalMass(), kGen1LightMass, 1e-6);
  EXPECT_NEAR(Shipped("gen4").TotalMass(), kGen4Mass, 1e-6);
  // The SPEC's mass is the real loads over g; 275.15 is it rounded to 10 g.
  EXPECT_NEAR(Shipped("gen4").TotalMass(), (kW1 + kW2 + kW3 + kW4) / 9.81, 0.005);
  EXPECT_NEAR(Shipped("gen1").TotalMass(), kGen1Mass, 1e-6);
  EXPECT_NEAR(Shipped("gen2").TotalMass(), kGen2Mass, 1e-6);
  for (const char* gen : {"gen2", "gen3", "gen4"}) {
    const Robot& r = Shipped(gen);
    ASSERT_NE(r.FindBody("FrontSupport"), nullptr) << gen;
    ASSERT_NE(r.FindBody("Torso"), nullptr) << gen;
    EXPECT_NEAR(r.FindBody("FrontSupport")->mass + r.FindBody("Torso")->mass, kSupportTorsoMass,
                1e-9)
        << gen;
  }
}

TEST(ShippedRobots, RequiredNamesExistInEveryGeneration) {
  for (const char* gen : kGenerations) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    ASSERT_NE(r.FindJoint("Turner"), nullptr);
    EXPECT_NE(r.FindBody("FrontChassis"), nullptr);
    EXPECT_NE(r.FindBody("RearChassis"), nullptr);
    EXPECT_NE(FindActuator(r, "TurnerMotor"), nullptr);
    for (int n = 1; n <= 4; ++n) {
      const std::string i = std::to_string(n);
      EXPECT_NE(r.FindBody("Wheel" + i), nullptr) << n;
      EXPECT_NE(r.FindBody("Calf" + i), nullptr) << n;
      EXPECT_NE(r.FindBody("Thigh" + i), nullptr) << n;
      for (const char* joint : {"Hip", "Knee", "Axle"}) {
        EXPECT_NE(r.FindJoint(joint + i), nullptr) << joint << n;
        EXPECT_NE(FindActuator(r, joint + i + "Motor"), nullptr) << joint << n;
      }
    }
    // Names are unique across bodies, joints, sensors and actuators.
    std::set<std::string> names;
    size_t count = 0;
    for (const Body& b : r.bodies) names.insert(b.name), ++count;
    for (const Joint& j : r.joints) names.insert(j.name), ++count;
    for (const Sensor& s : r.sensors) names.insert(s.name), ++count;
    for (const Actuator& a : r.actuators) names.insert(a.name), ++count;
    EXPECT_EQ(names.size(), count);
  }
}

TEST(ShippedRobots, WheelsAreNumberedAndPlacedPerSpec) {
  for (const char* gen : kGenerations) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    for (const WheelPlace& w : kWheels) {
      const std::string i = std::to_string(w.number);
      const Body* wheel = r.FindBody("Wheel" + i);
      ASSERT_NE(wheel, nullptr);
      EXPECT_EQ(wheel->geometry.kind, GeometryKind::kCylinder);
      EXPECT_DOUBLE_EQ(wheel->geometry.size.x(), kWheelRadius);
      const Eigen::Vector3d centre(w.x, kWheelRadius - LegDrop(gen, w.number), w.z);
      EXPECT_TRUE(Near(wheel->pose.translation(), centre, 1e-9))
          << "Wheel" << i << " at " << wheel->pose.translation().transpose();
      EXPECT_TRUE(Near(wheel->com, Eigen::Vector3d::Zero(), 1e-12));
      // Cylinder axis (body z) along the robot's z: the axle is lateral.
      EXPECT_NEAR(std::abs(wheel->pose.linear().col(2).z()), 1.0, 1e-9);
      // Axle: calf (body1) - wheel (body2) hinge about z through the centre.
      const Joint* axle = r.FindJoint("Axle" + i);
      ASSERT_NE(axle, nullptr);
      EXPECT_EQ(axle->kind, JointKind::kHinge);
      EXPECT_EQ(axle->body1, "Calf" + i);
      EXPECT_EQ(axle->body2, "Wheel" + i);
      EXPECT_TRUE(Near(axle->axis[0], Eigen::Vector3d::UnitZ(), 1e-12));
      EXPECT_TRUE(Near(axle->anchor, wheel->pose.translation(), 1e-9));
      const Actuator* motor = FindActuator(r, "Axle" + i + "Motor");
      ASSERT_NE(motor, nullptr);
      EXPECT_EQ(motor->kind, ActuatorKind::kJointVelocity);
      EXPECT_EQ(motor->joint, "Axle" + i);
      // Each wheel directly below its hip, in the hip's chassis half.
      const Joint* hip = r.FindJoint("Hip" + i);
      ASSERT_NE(hip, nullptr);
      EXPECT_NEAR(hip->anchor.x(), w.x, 1e-9);
      EXPECT_EQ(hip->body2, w.x > 0 ? "FrontChassis" : "RearChassis");
      EXPECT_EQ(hip->body1, "Thigh" + i);
      EXPECT_TRUE(Near(hip->axis[0].cwiseAbs(), Eigen::Vector3d::UnitZ(), 1e-12));
      const Joint* knee = r.FindJoint("Knee" + i);
      ASSERT_NE(knee, nullptr);
      EXPECT_EQ(knee->body1, "Calf" + i);
      EXPECT_EQ(knee->body2, "Thigh" + i);
      EXPECT_TRUE(Near(knee->axis[0].cwiseAbs(), Eigen::Vector3d::UnitZ(), 1e-12));
    }
  }
}

TEST(ShippedRobots, TurnerIsAVerticalHingeBetweenTheChassisHalves) {
  for (const char* gen : kGenerations) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    const Joint* turner = r.FindJoint("Turner");
    ASSERT_NE(turner, nullptr);
    EXPECT_EQ(turner->kind, JointKind::kHinge);
    EXPECT_TRUE(Near(turner->axis[0].cwiseAbs(), Eigen::Vector3d::UnitY(), 1e-12));
    EXPECT_NEAR(turner->anchor.x(), 0.0, 1e-12);  // origin directly below it
    EXPECT_NEAR(turner->anchor.z(), 0.0, 1e-12);
    const std::set<std::string> halves = {turner->body1, turner->body2};
    EXPECT_EQ(halves, (std::set<std::string>{"FrontChassis", "RearChassis"}));
    const Actuator* motor = FindActuator(r, "TurnerMotor");
    ASSERT_NE(motor, nullptr);
    EXPECT_EQ(motor->kind, ActuatorKind::kAngle);
    EXPECT_EQ(motor->joint, "Turner");
  }
}

TEST(ShippedRobots, OnlyTheWheelsTouchTheGroundAndNothingOverlaps) {
  for (const char* gen : kGenerations) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    std::set<std::pair<std::string, std::string>> jointed;
    for (const Joint& j : r.joints) {
      jointed.insert({j.body1, j.body2});
      jointed.insert({j.body2, j.body1});
    }
    for (const Body& b : r.bodies) {
      const Box3 box = Bounds(b);
      if (b.name.rfind("Wheel", 0) == 0) {
        // gen4's wheels 2 and 4 start kGen4LegOffset in the ground.
        EXPECT_NEAR(box.lo.y(), -LegDrop(gen, std::stoi(b.name.substr(5))), 1e-9) << b.name;
      } else {
        EXPECT_GT(box.lo.y(), 0.05) << b.name;
      }
    }
    // Bounding boxes are conservative: disjoint boxes cannot touch.
    for (size_t i = 0; i < r.bodies.size(); ++i) {
      for (size_t k = i + 1; k < r.bodies.size(); ++k) {
        const Body& a = r.bodies[i];
        const Body& b = r.bodies[k];
        if (jointed.count({a.name, b.name})) continue;
        const Box3 ba = Bounds(a), bb = Bounds(b);
        const bool disjoint = (ba.hi.array() <= bb.lo.array()).any() ||
                              (bb.hi.array() <= ba.lo.array()).any();
        EXPECT_TRUE(disjoint) << a.name << " and " << b.name << " overlap";
      }
    }
  }
}

TEST(ShippedRobots, NumericallySaneMasses) {
  for (const char* gen : kGenerations) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    for (const Body& b : r.bodies) EXPECT_GE(b.mass, 0.5) << b.name;
    for (const Joint& j : r.joints) {
      const double m1 = r.FindBody(j.body1)->mass, m2 = r.FindBody(j.body2)->mass;
      EXPECT_LE(std::max(m1, m2) / std::min(m1, m2), 50.0) << j.name;
    }
  }
}

TEST(ShippedRobots, EachGenerationHasItsParts) {
  // gen1: no torso, no sensors.
  for (const char* gen : {"gen1", "gen1_light"}) {
    const Robot& r = Shipped(gen);
    EXPECT_EQ(r.FindBody("Torso"), nullptr) << gen;
    EXPECT_TRUE(r.sensors.empty()) << gen;
    EXPECT_EQ(r.bodies.size(), 14u) << gen;  // 2 chassis halves + 4 x (thigh, calf, wheel)
  }
  // gen1_light is gen1's shape: same bodies, poses and shapes.
  {
    const Robot& heavy = Shipped("gen1");
    const Robot& light = Shipped("gen1_light");
    ASSERT_EQ(heavy.bodies.size(), light.bodies.size());
    for (const Body& b : heavy.bodies) {
      const Body* l = light.FindBody(b.name);
      ASSERT_NE(l, nullptr) << b.name;
      EXPECT_TRUE(l->pose.isApprox(b.pose, 1e-12)) << b.name;
      EXPECT_EQ(l->geometry.kind, b.geometry.kind) << b.name;
      EXPECT_TRUE(Near(l->geometry.size, b.geometry.size, 1e-12)) << b.name;
    }
    EXPECT_EQ(heavy.joints.size(), light.joints.size());
  }
  // gen2+: front support, torso turned by an angle controller about a
  // vertical axis, echo + position + scanner.
  for (const char* gen : {"gen2", "gen3", "gen4"}) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    const Joint* turn = r.FindJoint("TorsoTurn");
    ASSERT_NE(turn, nullptr);
    EXPECT_EQ(turn->kind, JointKind::kHinge);
    EXPECT_TRUE(Near(turn->axis[0].cwiseAbs(), Eigen::Vector3d::UnitY(), 1e-12));
    EXPECT_TRUE((turn->body1 == "Torso") != (turn->body2 == "Torso"));
    const Actuator* motor = FindActuator(r, "TorsoTurnMotor");
    ASSERT_NE(motor, nullptr);
    EXPECT_EQ(motor->kind, ActuatorKind::kAngle);
    std::map<SensorKind, int> kinds;
    for (const Sensor& s : r.sensors) ++kinds[s.kind];
    EXPECT_EQ(kinds[SensorKind::kScanner], 1);
    EXPECT_EQ(kinds[SensorKind::kPosition], 1);
    EXPECT_EQ(kinds[SensorKind::kEcho], 1);
    // The documented sensor ports (models/README.md).
    ASSERT_NE(FindSensor(r, "Echo"), nullptr);
    ASSERT_NE(FindSensor(r, "Position"), nullptr);
    ASSERT_NE(FindSensor(r, "Scanner"), nullptr);
    EXPECT_EQ(FindSensor(r, "Echo")->port, 1025);
    EXPECT_EQ(FindSensor(r, "Position")->port, 1026);
    EXPECT_EQ(FindSensor(r, "Scanner")->port, 1027);
    EXPECT_EQ(FindSensor(r, "Scanner")->kind, SensorKind::kScanner);
  }
  // gen3+: two manipulators, every arm joint angle controlled.
  for (const char* gen : {"gen3", "gen4"}) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    for (const char* side : {"Right", "Left"}) {
      for (const char* part : {"UpperArm", "LowerArm", "Wrist", "ClawUpper", "ClawLower"})
        EXPECT_NE(r.FindBody(std::string(side) + part), nullptr) << side << part;
      for (const char* joint : {"Shoulder", "Elbow", "WristTurn", "GripUpper", "GripLower"}) {
        const std::string name = std::string(side) + joint;
        const Joint* j = r.FindJoint(name);
        ASSERT_NE(j, nullptr) << name;
        EXPECT_EQ(j->kind, JointKind::kHinge) << name;
        const Actuator* a = FindActuator(r, name + "Motor");
        ASSERT_NE(a, nullptr) << name;
        EXPECT_EQ(a->kind, ActuatorKind::kAngle) << name;
        EXPECT_EQ(a->joint, name);
      }
      // The wrist turns about the lower arm (x in the start pose).
      EXPECT_TRUE(Near(r.FindJoint(std::string(side) + "WristTurn")->axis[0].cwiseAbs(),
                       Eigen::Vector3d::UnitX(), 1e-12));
    }
    // The right arm on the right (z > 0) of the torso, the left on the left.
    const double torso_z = r.FindBody("Torso")->pose.translation().z();
    EXPECT_GT(r.FindBody("RightUpperArm")->pose.translation().z(), torso_z);
    EXPECT_LT(r.FindBody("LeftUpperArm")->pose.translation().z(), torso_z);
    EXPECT_GE(r.bodies.size(), 24u);  // "about 25 bodies"
  }
  EXPECT_EQ(Shipped("gen2").FindBody("RightUpperArm"), nullptr);
  // gen4: rear support and a weight; the torso 5 cm to the left of gen3's.
  {
    const Robot& g4 = Shipped("gen4");
    EXPECT_NE(g4.FindBody("RearSupport"), nullptr);
    EXPECT_NE(g4.FindBody("Weight"), nullptr);
    EXPECT_EQ(Shipped("gen3").FindBody("Weight"), nullptr);
    const Eigen::Vector3d shift = g4.FindBody("Torso")->pose.translation() -
                                  Shipped("gen3").FindBody("Torso")->pose.translation();
    EXPECT_TRUE(Near(shift, Eigen::Vector3d(0, 0, -0.05), 1e-9)) << shift.transpose();
  }
}

TEST(ShippedRobots, ScannerLooksForwardFromTheTorsoAxis) {
  for (const char* gen : {"gen2", "gen3", "gen4"}) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    const Sensor* scanner = nullptr;
    for (const Sensor& s : r.sensors)
      if (s.kind == SensorKind::kScanner) scanner = &s;
    ASSERT_NE(scanner, nullptr);
    EXPECT_EQ(scanner->rays, kScannerRays);
    EXPECT_DOUBLE_EQ(scanner->half_span, kScannerHalfSpan);
    EXPECT_DOUBLE_EQ(scanner->range, kScannerRange);
    EXPECT_EQ(scanner->body, "Torso");
    const Body* torso = r.FindBody("Torso");
    ASSERT_NE(torso, nullptr);
    const Eigen::Isometry3d frame = torso->pose * scanner->mount;  // in the robot frame
    EXPECT_NEAR(frame.translation().x(), kScannerAhead, 1e-9);
    EXPECT_GT(frame.translation().y(), 0.5);
    // Rays fan around the sensor's z axis in its z-x plane: z forward, y up.
    EXPECT_TRUE(Near(frame.linear().col(2), Eigen::Vector3d::UnitX(), 1e-9));
    EXPECT_TRUE(Near(frame.linear().col(1), Eigen::Vector3d::UnitY(), 1e-9));
    // On the torso's vertical turning axis: turning moves it not.
    const Joint* turn = r.FindJoint("TorsoTurn");
    ASSERT_NE(turn, nullptr);
    EXPECT_NEAR(frame.translation().x(), turn->anchor.x(), 1e-9);
    EXPECT_NEAR(frame.translation().z(), turn->anchor.z(), 1e-9);
  }
}

TEST(ShippedRobots, LegacyPortsAreUniqueAndStableAcrossGenerations) {
  std::map<std::string, int> port_of;  // name -> port, across all generations
  for (const char* gen : kGenerations) {
    SCOPED_TRACE(gen);
    const Robot& r = Shipped(gen);
    std::set<int> ports;
    auto check = [&](const std::string& name, int port) {
      EXPECT_GT(port, 1024) << name;
      EXPECT_TRUE(ports.insert(port).second) << name << " reuses port " << port;
      const auto [it, inserted] = port_of.emplace(name, port);
      if (!inserted) {
        EXPECT_EQ(it->second, port) << name << " changes port between generations";
      }
    };
    // The original addressed every sensor by port; the sensors that came
    // after it (the field sensors, the Camera) have none.
    for (const Sensor& s : r.sensors) {
      if (NeedsRate(s.kind) || s.kind == SensorKind::kCamera)
        EXPECT_EQ(s.port, 0) << s.name;
      else
        check(s.name, s.port);
    }
    for (const Actuator& a : r.actuators) check(a.name, a.port);
    // Every actuated joint has a motor; every non-fixed joint is actuated
    // (a free joint would let the robot collapse).
    std::set<std::string> driven;
    for (const Actuator& a : r.actuators) driven.insert(a.joint);
    for (const Joint& j : r.joints) {
      if (j.kind != JointKind::kFixed) {
        EXPECT_EQ(driven.count(j.name), 1u) << j.name;
      }
    }
  }
  // The SPEC's sequencer example sends a 6-value joint-controller command to
  // port 1028; ours is Axle1Motor (wheel 1's velocity).
  for (const char* gen : kGenerations) {
    const Actuator* a = FindActuator(Shipped(gen), "Axle1Motor");
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->port, 1028) << gen;
    EXPECT_EQ(a->kind, ActuatorKind::kJointVelocity) << gen;
  }
}

// gen4's legs are gen3's, with legs 2 and 4 moved down as a whole (hip,
// knee and axle anchors, thigh, calf and wheel): longer legs, same shape.
TEST(ShippedRobots, Gen4LegsTwoAndFourAreLongerAsAWhole) {
  const Robot& g3 = Shipped("gen3");
  const Robot& g4 = Shipped("gen4");
  for (int n = 1; n <= 4; ++n) {
    const std::string i = std::to_string(n);
    const Eigen::Vector3d drop(0, -LegDrop("gen4", n), 0);
    for (const char* part : {"Thigh", "Calf", "Wheel"}) {
      const Body* b3 = g3.FindBody(part + i);
      const Body* b4 = g4.FindBody(part + i);
      ASSERT_NE(b3, nullptr);
      ASSERT_NE(b4, nullptr);
      EXPECT_TRUE(Near(b4->pose.translation() - b3->pose.translation(), drop, 1e-12)) << part << n;
      EXPECT_TRUE(b4->pose.linear().isApprox(b3->pose.linear(), 1e-12)) << part << n;
    }
    for (const char* joint : {"Hip", "Knee", "Axle"}) {
      const Joint* j3 = g3.FindJoint(joint + i);
      const Joint* j4 = g4.FindJoint(joint + i);
      ASSERT_NE(j3, nullptr);
      ASSERT_NE(j4, nullptr);
      EXPECT_TRUE(Near(j4->anchor - j3->anchor, drop, 1e-12)) << joint << n;
    }
  }
}

// The tyre material: a physical stiffness and damping of the whole contact
// (the sim turns them into ERP/CFM for the step size), shared by a wheel's
// two contact points.
TEST(ShippedRobots, Gen4TyresHaveTheirStiffnessAndDamping) {
  const Robot& r = Shipped("gen4");
  const Material* tyre = nullptr;
  for (int n = 1; n <= 4; ++n) {
    const Body* wheel = r.FindBody("Wheel" + std::to_string(n));
    ASSERT_NE(wheel, nullptr);
    for (const Material& m : r.materials)
      if (m.name == wheel->material) tyre = &m;
    ASSERT_NE(tyre, nullptr) << "Wheel" << n;
  }
  ASSERT_TRUE(tyre->HasStiffness());
  ASSERT_TRUE(tyre->damping.has_value());
  EXPECT_EQ(*tyre->stiffness, kGen4TyreStiffness);
  EXPECT_EQ(*tyre->damping, kGen4TyreDamping);
  // Softer than a ground without material at every step size up to 2 ms
  // (ERP / (h CFM) = 1e7 N/m there), so the tyre decides the contact.
  EXPECT_LT(*tyre->stiffness, kDefaultSoftERP / (0.002 * kDefaultSoftCFM));
  // ODE caps ERP * depth / h at contactMaxCorrectingVel; standing, that is
  // F_p / (h k_p + c_p), so a point gives way above 0.2 (h k_p + c_p). The
  // heaviest static point load is under 400 N (a wheel's 775 N and its
  // share of the roll moment); leave a factor of 1.5 for driving, at the
  // smallest step of the step-size test (0.5 ms).
  const double k_point = *tyre->stiffness / 2.0, c_point = *tyre->damping / 2.0;
  EXPECT_GT(kMaxCorrectingVel * (0.0005 * k_point + c_point), 1.5 * 400.0);
}

// gen4's loads on flat ground as a spring model of its supports (the
// arithmetic is written out in workpartner_gen4.xml): each wheel is its
// tyre (two contact points of k_p) in series with its leg, whose axle, knee
// and hip hinges yield like springs of ERP / (h CFM) per position row and
// whose knee (0.18 m beside the axle) is held with kHoldGain / CFM N m per
// radian:  k_v = 1 / (1 / (2 k_p) + 3 h CFM / ERP + 0.18^2 CFM / G).
//  - total = M g;
//  - cross weight: legs 2 and 4 are delta longer; on flat ground the
//    chassis settles halfway, (W2 + W4) - (W1 + W3) = 2 k_v delta;
//  - splits, from moments about the ground-level axes with the robot
//    leaning on its supports (its centre of mass moves over by its height
//    h_c times the angle) and, in roll, each wheel also carrying a moment
//    through its two contact points at +-0.07 m:
//      front - rear = 4 k_v a W x / (4 k_v a^2 - W h_c),
//      left - right = 4 k_v t W z_left / (4 k_v t^2 + 8 k_p 0.07^2 - W h_c).
// The real robot's sums within 0.5 N: the file rounds its positions to
// 0.1 um and 1 um, less than 0.1 N here.
TEST(ShippedRobots, Gen4SupportsAndCentreOfMassGiveTheRealStaticLoads) {
  const Robot& r = Shipped("gen4");
  const Eigen::Vector3d com = CentreOfMass(r);
  const double weight = r.TotalMass() * 9.81;
  EXPECT_NEAR(weight, kW1 + kW2 + kW3 + kW4, 0.05);  // 275.15 kg is rounded to 10 g
  double k_point = 0.0;  // the tyre's stiffness per contact point, two per wheel
  for (const Material& m : r.materials)
    if (m.name == r.FindBody("Wheel1")->material && m.HasStiffness()) k_point = *m.stiffness / 2.0;
  ASSERT_GT(k_point, 0.0);
  const double knee_lever = 0.18;  // knee to axle, along x (models/README.md)
  const double k_v = 1.0 / (1.0 / (2.0 * k_point) + 3.0 * kStep * kGlobalCFM / kGlobalERP +
                            knee_lever * knee_lever * kGlobalCFM / kHoldGain);
  // The wheels sink weight / (4 k) into the ground from the file's pose.
  const double height = com.y() - weight / (4.0 * 2.0 * k_point);
  const double front_minus_rear =
      4.0 * k_v * kAxleX * weight * com.x() / (4.0 * k_v * kAxleX * kAxleX - weight * height);
  const double left_minus_right =
      4.0 * k_v * kHalfTrack * weight * -com.z() /
      (4.0 * k_v * kHalfTrack * kHalfTrack + 8.0 * k_point * 0.07 * 0.07 - weight * height);
  const double cross = 2.0 * k_v * kGen4LegOffset;
  EXPECT_NEAR(front_minus_rear, (kW1 + kW2) - (kW3 + kW4), 0.5);
  EXPECT_NEAR(left_minus_right, (kW2 + kW3) - (kW1 + kW4), 0.5);
  EXPECT_NEAR(cross, (kW2 + kW4) - (kW1 + kW3), 0.5);
  // Point supports would need the centre of mass 0.3 * 188.84 / 2699.2 =
  // 0.0210 m to the left; the wheels' line contact and the lean move it to
  // 0.0216 m.
  EXPECT_GT(-com.z(), 0.3 * ((kW2 + kW3) - (kW1 + kW4)) / (kW1 + kW2 + kW3 + kW4) + 0.0005);
}

TEST(ShippedRobots, Gen3IsHeavierAtTheFrontAsTheOriginal) {
  // The original's pole run: about 700 N per front and 350 N per rear wheel;
  // gen3 alone must already load its front wheels more than its rear ones.
  const Eigen::Vector3d com = CentreOfMass(Shipped("gen3"));
  EXPECT_GT(com.x(), 0.1);
  EXPECT_LT(com.x(), 0.3);
  EXPECT_NEAR(com.z(), 0.0, 1e-9);  // symmetric left/right
}

}  // namespace
}  // namespace simpartner::model
