// The physical ranges of models/README.md ("Physical ranges"): each value
// that made ODE abort the sim after --check had passed it (SimPartner issue
// 10: masses 1e308, 4.9e-324 and 1e-12 kg, sizes 1e-310 and 1e100 m, a robot
// placed 1e10 m away, a velocity of 1e308) is refused as
// file:line: element: message naming the allowed range, and values at the
// edges of the ranges still load. The ranges are written here as the
// README states them, not taken from the code.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "simpartner/model/loader.h"
#include "simpartner/text.h"

namespace simpartner::model {
namespace {

std::string Pose(double x, double y, double z) {
  return "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>" + ShortestNumber(x) +
         "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" + ShortestNumber(y) +
         "</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>" + ShortestNumber(z) + "</T23></transformation>";
}

std::string Xyz(const char* tag, double x, double y, double z, const char* cx = "x",
                const char* cy = "y", const char* cz = "z") {
  return std::string("<") + tag + "><" + cx + ">" + ShortestNumber(x) + "</" + cx + "><" + cy + ">" +
         ShortestNumber(y) + "</" + cy + "><" + cz + ">" + ShortestNumber(z) + "</" + cz + "></" + tag + ">";
}

// One object per line so that each element's line is known: line 1 is
// <world>, the object's elements are on lines 2 (object), 3 (mass), 4
// (size or radius), 5 (transformation), 6 (translationalVelocity), 7
// (rotationalVelocity).
struct ObjectSpec {
  std::string type = "Box";
  double mass = 1.0;
  double size[3] = {1.0, 1.0, 1.0};  // Box: x y z; Sphere: radius
  double position[3] = {0.0, 0.5, 0.0};
  double velocity[3] = {0.0, 0.0, 0.0};
  double rotation[3] = {0.0, 0.0, 0.0};
};

std::string ObjectWorld(const ObjectSpec& o) {
  const std::string size = o.type == "Box" ? Xyz("size", o.size[0], o.size[1], o.size[2])
                                           : "<radius>" + ShortestNumber(o.size[0]) + "</radius>";
  return "<world name=\"W\">\n"
         "<object type=\"" + o.type + "\" name=\"Thing\">\n"
         "<mass>" + ShortestNumber(o.mass) + "</mass>\n" +
         size + "\n" +
         Pose(o.position[0], o.position[1], o.position[2]) + "\n" +
         Xyz("translationalVelocity", o.velocity[0], o.velocity[1], o.velocity[2], "vx", "vy",
             "vz") + "\n" +
         Xyz("rotationalVelocity", o.rotation[0], o.rotation[1], o.rotation[2], "omegax",
             "omegay", "omegaz") + "\n"
         "</object>\n</world>\n";
}

struct RangeCase {
  const char* name;
  ObjectSpec object;
  std::string diagnostic;  // the one expected, formatted
};

std::vector<RangeCase> ObjectCases() {
  std::vector<RangeCase> cases;
  auto add = [&](const char* name, auto change, const std::string& diagnostic) {
    ObjectSpec o;
    change(o);
    cases.push_back({name, o, diagnostic});
  };
  const std::string mass_range = " kg is out of range [0.0001, 1000000] kg";
  add("mass 1e308 kg", [](ObjectSpec& o) { o.mass = 1e308; },
      "w.xml:3: mass: object 'Thing': mass 1e+308" + mass_range);
  add("mass 4.9e-324 kg", [](ObjectSpec& o) { o.mass = 4.9e-324; },
      "w.xml:3: mass: object 'Thing': mass 4.940656458e-324" + mass_range);
  add("mass 1e-12 kg", [](ObjectSpec& o) { o.mass = 1e-12; },
      "w.xml:3: mass: object 'Thing': mass 1e-12" + mass_range);
  add("mass just below 0.1 g", [](ObjectSpec& o) { o.mass = 0.99e-4; },
      "w.xml:3: mass: object 'Thing': mass 9.9e-05" + mass_range);
  add("mass just above 1000 t", [](ObjectSpec& o) { o.mass = 1.01e6; },
      "w.xml:3: mass: object 'Thing': mass 1010000" + mass_range);
  add("size 1e-310 m",
      [](ObjectSpec& o) {
        o.type = "Sphere";
        o.size[0] = 1e-310;
      },
      "w.xml:4: radius: object 'Thing': radius 1e-310 m is out of range [0.001, 10000] m");
  add("size 1e100 m", [](ObjectSpec& o) { o.size[1] = 1e100; },
      "w.xml:4: size: object 'Thing': size y 1e+100 m is out of range [0.001, 10000] m");
  add("placed 1e10 m away", [](ObjectSpec& o) { o.position[0] = 1e10; },
      "w.xml:5: transformation: object 'Thing': position (1e+10, 0.5, 0) m is out of range: "
      "|x|, |y|, |z| <= 1000000 m");
  add("velocity 1e308 m/s", [](ObjectSpec& o) { o.velocity[0] = 1e308; },
      "w.xml:6: translationalVelocity: object 'Thing': translationalVelocity (1e+308, 0, 0) m/s "
      "is out of range: speed at most 10000 m/s");
  add("rotation 1e308 rad/s", [](ObjectSpec& o) { o.rotation[2] = 1e308; },
      "w.xml:7: rotationalVelocity: object 'Thing': rotationalVelocity (0, 0, 1e+308) rad/s is "
      "out of range: rotation at most 10000 rad/s");
  // A 1 kg rod of 1 mm x 10 km x 1 mm: about its length m (2 mm^2) / 12,
  // across it m (10 km)^2 / 12, a factor of 5e13.
  add("inertia ratio of a needle",
      [](ObjectSpec& o) {
        o.size[0] = 1e-3;
        o.size[1] = 1e4;
        o.size[2] = 1e-3;
        o.position[1] = 5000;
      },
      "w.xml:2: object: object 'Thing': principal moments of inertia (1.666666667e-07, "
      "8333333.333, 8333333.333) kg m^2 (of a uniform Box of this mass and size) differ by a "
      "factor of 5e+13; at most 1000000");
  return cases;
}

TEST(PhysicalRanges, EachOutOfRangeObjectValueIsRefusedWithItsRange) {
  for (const RangeCase& c : ObjectCases()) {
    const WorldLoadResult result = ParseWorld(ObjectWorld(c.object), "w.xml");
    EXPECT_FALSE(result.world.has_value()) << c.name;
    ASSERT_EQ(result.diagnostics.size(), 1u) << c.name << ":\n" << result.diagnostics.Format();
    EXPECT_EQ(result.diagnostics.items()[0].Format(), c.diagnostic) << c.name;
  }
}

TEST(PhysicalRanges, ValuesAtTheEdgesOfTheRangesLoad) {
  std::vector<std::pair<const char*, ObjectSpec>> edges;
  auto add = [&](const char* name, auto change) {
    ObjectSpec o;
    change(o);
    edges.emplace_back(name, o);
  };
  add("mass 0.1 g (a 1 cm sphere)", [](ObjectSpec& o) {
    o.type = "Sphere";
    o.mass = 1e-4;
    o.size[0] = 0.01;
  });
  add("mass 1000 t", [](ObjectSpec& o) { o.mass = 1e6; });
  add("size 1 mm", [](ObjectSpec& o) {
    o.size[0] = o.size[1] = o.size[2] = 1e-3;
    o.position[1] = 5e-4;
  });
  add("size 10 km", [](ObjectSpec& o) {
    o.size[0] = o.size[1] = o.size[2] = 1e4;
    o.position[1] = 5000;
  });
  add("1000 km away", [](ObjectSpec& o) { o.position[0] = o.position[2] = -1e6; });
  add("10 km/s", [](ObjectSpec& o) { o.velocity[1] = 1e4; });
  add("10000 rad/s", [](ObjectSpec& o) { o.rotation[0] = 1e4; });
  for (const auto& [name, object] : edges) {
    const WorldLoadResult result = ParseWorld(ObjectWorld(object), "w.xml");
    EXPECT_TRUE(result.world.has_value()) << name << ":\n" << result.diagnostics.Format();
  }
}

// A static object's mass is not used (it does not move), so only its
// shape and place are held to the ranges.
TEST(PhysicalRanges, StaticObjectMassIsNotLimited) {
  const std::string world = "<world name=\"W\">\n<object type=\"Box\" name=\"Wall\" static=\"true\">"
                            "<mass>1e12</mass>" + Xyz("size", 1, 1, 1) + Pose(0, 0.5, 0) +
                            "</object>\n</world>\n";
  const WorldLoadResult result = ParseWorld(world, "w.xml");
  EXPECT_TRUE(result.world.has_value()) << result.diagnostics.Format();
}

// Two boxes on a hinge: A (mass_a) on line 2, B (mass_b) on line 3, the
// joint on line 4.
std::string PairRobot(double mass_a, double mass_b, double anchor_x = 0.5) {
  return "<robot name=\"Pair\">\n"
         "<body type=\"Box\" name=\"A\"><mass>" + ShortestNumber(mass_a) + "</mass>" + Xyz("size", 1, 1, 1) +
         Pose(0, 0.5, 0) + "</body>\n"
         "<body type=\"Box\" name=\"B\"><mass>" + ShortestNumber(mass_b) + "</mass>" +
         Xyz("size", 1, 1, 1) + Pose(1, 0.5, 0) + "</body>\n"
         "<joint type=\"Hinge\" name=\"J\"><body1>A</body1><body2>B</body2>" +
         Xyz("anchor", anchor_x, 0.5, 0) + Xyz("axis1", 0, 0, 1) + "</joint>\n</robot>\n";
}

TEST(PhysicalRanges, MassRatioAcrossAJointIsAtMost1e4) {
  EXPECT_TRUE(ParseRobot(PairRobot(10, 1e-3), "r.xml").robot.has_value());
  const RobotLoadResult result = ParseRobot(PairRobot(10, 0.9e-3), "r.xml");
  EXPECT_FALSE(result.robot.has_value());
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].Format(),
            "r.xml:4: joint: joint 'J': body 'A' (10 kg) is 11111.11111 times as heavy as body "
            "'B' (0.0009 kg); across a joint at most 10000");
}

TEST(PhysicalRanges, MassRatioWithinARobotIsAtMost1e6) {
  // A chain A - B - C: each joint within 1e4, A to C 1.5e6.
  const std::string robot =
      "<robot name=\"Chain\">\n"
      "<body type=\"Box\" name=\"A\"><mass>150000</mass>" + Xyz("size", 1, 1, 1) +
      Pose(0, 0.5, 0) + "</body>\n"
      "<body type=\"Box\" name=\"B\"><mass>15</mass>" + Xyz("size", 1, 1, 1) + Pose(1, 0.5, 0) +
      "</body>\n"
      "<body type=\"Box\" name=\"C\"><mass>0.1</mass>" + Xyz("size", 1, 1, 1) + Pose(2, 0.5, 0) +
      "</body>\n"
      "<joint type=\"Fixed\" name=\"AB\"><body1>A</body1><body2>B</body2></joint>\n"
      "<joint type=\"Fixed\" name=\"BC\"><body1>B</body1><body2>C</body2></joint>\n</robot>\n";
  const RobotLoadResult result = ParseRobot(robot, "r.xml");
  EXPECT_FALSE(result.robot.has_value());
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].Format(),
            "r.xml:4: body: body 'C' (0.1 kg) is 1500000 times lighter than body 'A' (150000 "
            "kg); within a robot at most 1000000");
}

TEST(PhysicalRanges, JointAnchorOutOfRangeIsRefused) {
  const RobotLoadResult result = ParseRobot(PairRobot(1, 1, 2e6), "r.xml");
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].Format(),
            "r.xml:4: anchor: joint 'J': anchor (2000000, 0.5, 0) m is out of range: |x|, |y|, "
            "|z| <= 1000000 m");
}

// A scanner's rays start at its mount: a mount 1e10 m off is refused.
TEST(PhysicalRanges, SensorMountOutOfRangeIsRefused) {
  std::string robot = PairRobot(1, 1);
  robot.insert(robot.rfind("</robot>"),
               "<sensor type=\"Scanner\" name=\"S\"><bodyRef>A</bodyRef>" + Pose(1e10, 0, 0) +
                   "</sensor>\n");
  const RobotLoadResult result = ParseRobot(robot, "r.xml");
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].Format(),
            "r.xml:5: transformation: sensor 'S': mount position (1e+10, 0, 0) m is out of "
            "range: |x|, |y|, |z| <= 1000000 m");
}

// The robot files are fine; the world places the robot out of range.
TEST(PhysicalRanges, RobotPlacedOutOfRangeIsRefusedAtThePlacement) {
  const std::string world = "<world name=\"W\">\n<robot name=\"R\" file=\"pair.xml\">\n" +
                            Pose(1e10, 0, 0) + "\n</robot>\n</world>\n";
  const FileReader reader = [](const std::string& path, std::string* out) {
    if (path != "pair.xml") return false;
    *out = PairRobot(1, 1);
    return true;
  };
  const WorldLoadResult result = ParseWorld(world, "w.xml", reader);
  EXPECT_FALSE(result.world.has_value());
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].Format(),
            "w.xml:3: transformation: robot 'R': placed at (1e+10, 0, 0) m, its body 'A' is at "
            "(1e+10, 0.5, 0) m, out of range: |x|, |y|, |z| <= 1000000 m");
  // 999 km away is fine.
  const std::string near = "<world name=\"W\">\n<robot name=\"R\" file=\"pair.xml\">\n" +
                           Pose(999e3, 0, 0) + "\n</robot>\n</world>\n";
  EXPECT_TRUE(ParseWorld(near, "w.xml", reader).world.has_value());
}

// A heightfield's heights (offset + scale x sample) are coordinates too: a
// sample of 1e300 passed --check and made ODE fail in the first step.
TEST(PhysicalRanges, HeightfieldHeightsAndExtentAreLimited) {
  auto field = [](const std::string& width, const std::string& scale,
                  const std::string& second_row) {
    return "<world name=\"W\">\n<heightfield rows=\"2\" columns=\"2\">\n<width>" + width +
           "</width>\n<depth>10</depth>\n<scale>" + scale + "</scale>\n<samples>\n0 0\n" +
           second_row + "\n</samples>\n</heightfield>\n</world>\n";
  };
  const WorldLoadResult huge = ParseWorld(field("10", "1", "0 1e300"), "w.xml");
  ASSERT_EQ(huge.diagnostics.size(), 1u) << huge.diagnostics.Format();
  EXPECT_EQ(huge.diagnostics.items()[0].Format(),
            "w.xml:8: samples: heightfield sample 4 (row 2, column 2) '1e300' gives a height of "
            "1e+300 m (offset + scale x sample), out of range: |y| <= 1000000 m");
  // The scale counts: 2000 mm samples at 1000 m per unit are 2e6 m high.
  const WorldLoadResult scaled = ParseWorld(field("10", "1000", "2000 0"), "w.xml");
  ASSERT_EQ(scaled.diagnostics.size(), 1u) << scaled.diagnostics.Format();
  EXPECT_EQ(scaled.diagnostics.items()[0].Format(),
            "w.xml:8: samples: heightfield sample 3 (row 2, column 1) '2000' gives a height of "
            "2000000 m (offset + scale x sample), out of range: |y| <= 1000000 m");
  const WorldLoadResult wide = ParseWorld(field("1e7", "1", "0 0"), "w.xml");
  ASSERT_EQ(wide.diagnostics.size(), 1u) << wide.diagnostics.Format();
  EXPECT_EQ(wide.diagnostics.items()[0].Format(),
            "w.xml:3: width: heightfield width 10000000 m is out of range (0, 1000000] m");
  EXPECT_TRUE(ParseWorld(field("1e6", "0.001", "1e9 -1e9"), "w.xml").world.has_value());
}

}  // namespace
}  // namespace simpartner::model
