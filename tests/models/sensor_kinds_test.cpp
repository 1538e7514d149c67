// The sensor kinds with parameters in robot files (Imu, Gnss, Encoder,
// Lidar, Contact) and the world's geodetic origin: what a good file gives,
// and every bad value refused at its own line. Lines are found in the XML by a
// marker, never taken from the loader.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "model_test_support.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/model_message.h"
#include "simpartner/model/sensor_parameters.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner::model {
namespace {

using testing::LineOf;
using testing::Pose;

// Two boxes on a hinge and a slider, and `sensors` after them.
std::string RobotWith(const std::string& sensors) {
  return R"(<robot name="Bot">
  <body type="Box" name="Base"><mass>10</mass><size><x>1</x><y>1</y><z>1</z></size>)" +
         Pose(0, 0.5, 0) + R"(</body>
  <body type="Box" name="Top"><mass>1</mass><size><x>1</x><y>0.1</y><z>1</z></size>)" +
         Pose(0, 1.05, 0) + R"(</body>
  <body type="Box" name="Side"><mass>1</mass><size><x>0.1</x><y>0.1</y><z>0.1</z></size>)" +
         Pose(1, 0.5, 0) + R"(</body>
  <joint type="Hinge" name="Turn"><body1>Top</body1><body2>Base</body2>
    <anchor><x>0</x><y>1</y><z>0</z></anchor><axis1><x>0</x><y>1</y><z>0</z></axis1></joint>
  <joint type="Slider" name="Slide"><body1>Side</body1><body2>Base</body2>
    <axis1><x>1</x><y>0</y><z>0</z></axis1></joint>
)" + sensors + "\n</robot>";
}

TEST(SensorKinds, EveryKindWithItsParametersAndDefaults) {
  const std::string xml = RobotWith(R"(
  <sensor type="Imu" name="Imu"><bodyRef>Top</bodyRef><rate>200</rate>
    <parameter name="accelNoiseDensity">0.002</parameter>
    <parameter name="gyroBiasZ">-0.01</parameter></sensor>
  <sensor type="Gnss" name="Gnss"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="horizontalNoise">1.5</parameter></sensor>
  <sensor type="Encoder" name="Enc"><jointRef>Turn</jointRef><rate>100</rate>
    <parameter name="countsPerRevolution">4096</parameter></sensor>
  <sensor type="Lidar" name="Lidar"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="layers">4</parameter><parameter name="rays">90</parameter></sensor>
  <sensor type="Contact" name="Bumper"><bodyRef>Base</bodyRef><rate>50</rate></sensor>)");
  const RobotLoadResult result = ParseRobot(xml, "bot.xml");
  ASSERT_TRUE(result.robot) << result.diagnostics.Format();
  const std::vector<Sensor>& s = result.robot->sensors;
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0].kind, SensorKind::kImu);
  EXPECT_EQ(s[0].rate, 200.0);
  ASSERT_EQ(s[0].parameters.size(), static_cast<size_t>(imu_param::kCount));
  EXPECT_EQ(s[0].parameters[imu_param::kAccelNoiseDensity], 0.002);
  EXPECT_EQ(s[0].parameters[imu_param::kGyroBiasZ], -0.01);
  EXPECT_EQ(s[0].parameters[imu_param::kGyroNoiseDensity], 0.0);  // noise-free unless asked
  EXPECT_EQ(s[1].kind, SensorKind::kGnss);
  EXPECT_EQ(s[1].parameters[gnss_param::kHorizontalNoise], 1.5);
  EXPECT_EQ(s[1].parameters[gnss_param::kVerticalNoise], 0.0);
  EXPECT_EQ(s[2].kind, SensorKind::kEncoder);
  EXPECT_EQ(s[2].joint, "Turn");
  EXPECT_EQ(s[2].body, "Base");  // the joint's body2, as for ForceTorque
  EXPECT_EQ(s[2].parameters[encoder_param::kCountsPerRevolution], 4096.0);
  EXPECT_EQ(s[3].kind, SensorKind::kLidar);
  EXPECT_EQ(s[3].parameters[lidar_param::kLayers], 4.0);
  EXPECT_EQ(s[3].parameters[lidar_param::kRays], 90.0);
  EXPECT_EQ(s[3].parameters[lidar_param::kRange], 100.0);
  EXPECT_EQ(s[4].kind, SensorKind::kContact);
  EXPECT_EQ(s[4].parameters[contact_param::kThreshold], 0.0);
}

TEST(SensorKinds, SimModelCarriesKindsParamsAndTheGeodeticOrigin) {
  const std::string world_xml = R"(<world name="W">
  <geodeticOrigin><latitude>60.1867</latitude><longitude>24.8283</longitude><altitude>12.5</altitude></geodeticOrigin>
  <robot name="R" file="bot.xml"/>
</world>)";
  const std::string robot = RobotWith(R"(
  <sensor type="Gnss" name="Gnss"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="verticalNoise">3</parameter></sensor>
  <sensor type="Encoder" name="Enc"><jointRef>Turn</jointRef><rate>100</rate></sensor>)");
  const FileReader files = [&](const std::string& path, std::string* out) {
    if (path != "bot.xml") return false;
    *out = robot;
    return true;
  };
  const WorldLoadResult result = ParseWorld(world_xml, "w.xml", files);
  ASSERT_TRUE(result.world) << result.diagnostics.Format();
  ASSERT_TRUE(result.world->geodetic_origin);
  EXPECT_EQ(result.world->geodetic_origin->latitude, 60.1867);
  EXPECT_EQ(result.world->geodetic_origin->where.line, LineOf(world_xml, "<geodeticOrigin>"));
  const model_t m = ModelMessageFromWorld(*result.world);
  ASSERT_EQ(m.sensors.size(), 2u);
  EXPECT_EQ(m.sensors[0].kind, sensor_t::KIND_GNSS);
  EXPECT_EQ(m.sensors[0].params,
            (std::vector<double>{0, 3, 0, 0, 60.1867, 24.8283, 12.5}));
  EXPECT_EQ(m.sensors[1].kind, sensor_t::KIND_ENCODER);
  EXPECT_EQ(m.sensors[1].joint, 0);
  EXPECT_EQ(m.sensors[1].params, (std::vector<double>{1024}));
}

// One bad sensor: the one diagnostic it gives, at the line of marker, with
// `words` in its message.
void ExpectRefused(const std::string& sensor, const std::string& marker, const std::string& words) {
  const std::string xml = RobotWith(sensor);
  const RobotLoadResult result = ParseRobot(xml, "bad.xml");
  EXPECT_FALSE(result.robot) << sensor;
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.file, "bad.xml");
  EXPECT_EQ(d.line, LineOf(xml, marker)) << d.message;
  EXPECT_NE(d.message.find(words), std::string::npos) << d.message;
}

TEST(SensorKinds, BadParametersAreRefusedAtTheirLine) {
  ExpectRefused(R"(<sensor type="Imu" name="I"><bodyRef>Top</bodyRef><rate>100</rate>
    <parameter name="accelNoiseDensity">-0.1</parameter></sensor>)",
                "-0.1", "accelNoiseDensity -0.1 m/s^2/sqrt(Hz) is out of range [0, 10]");
  ExpectRefused(R"(<sensor type="Imu" name="I"><bodyRef>Top</bodyRef>
    <rate>0</rate></sensor>)",
                "<rate>0</rate>", "must be above 0 Hz");
  ExpectRefused(R"(<sensor type="Gnss" name="NoRate"><bodyRef>Top</bodyRef></sensor>)",
                "name=\"NoRate\"", "must be above 0 Hz");
  ExpectRefused(R"(<sensor type="Gnss" name="G"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="verticalNoise">-1</parameter></sensor>)",
                "-1<", "verticalNoise -1 m is out of range");
  ExpectRefused(R"(<sensor type="Encoder" name="E"><jointRef>Turn</jointRef><rate>100</rate>
    <parameter name="countsPerRevolution">0</parameter></sensor>)",
                "countsPerRevolution\">0", "countsPerRevolution 0 is out of range [1, 1000000000]");
  ExpectRefused(R"(<sensor type="Encoder" name="E"><jointRef>Turn</jointRef><rate>100</rate>
    <parameter name="countsPerRevolution">2.5</parameter></sensor>)",
                "2.5", "countsPerRevolution must be a whole number, got 2.5");
  ExpectRefused(R"(<sensor type="Encoder" name="E"><jointRef>Nowhere</jointRef><rate>1</rate></sensor>)",
                "Nowhere", "'Nowhere' is not a joint of robot 'Bot'");
  ExpectRefused(R"(<sensor type="Encoder" name="E"><jointRef>Slide</jointRef><rate>1</rate></sensor>)",
                ">Slide<", "an Encoder counts the turns of a Hinge; 'Slide' is a Slider joint");
  ExpectRefused(R"(<sensor type="Encoder" name="E"><bodyRef>Top</bodyRef><rate>1</rate></sensor>)",
                "name=\"E\"", "an Encoder sensor measures a joint: it needs <jointRef>");
  ExpectRefused(R"(<sensor type="Contact" name="C"><bodyRef>Ghost</bodyRef><rate>1</rate></sensor>)",
                "Ghost", "'Ghost' is not a body of robot 'Bot'");
  ExpectRefused(R"(<sensor type="Lidar" name="L"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="layers">0</parameter></sensor>)",
                "layers\">0", "layers 0 is out of range [1, 1024]");
  ExpectRefused(R"(<sensor type="Lidar" name="MinMax"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="minRange">5</parameter><parameter name="range">5</parameter></sensor>)",
                "name=\"MinMax\"", "minRange 5 m is not below range 5 m");
  ExpectRefused(R"(<sensor type="Lidar" name="Upside"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="lowestElevation">0.2</parameter><parameter name="highestElevation">0.1</parameter></sensor>)",
                "name=\"Upside\"", "lowestElevation 0.2 rad is above highestElevation 0.1 rad");
  ExpectRefused(R"(<sensor type="Lidar" name="Flood"><bodyRef>Top</bodyRef><rate>1000</rate>
    <parameter name="layers">64</parameter><parameter name="rays">1000</parameter></sensor>)",
                "name=\"Flood\"", "rays/s is more than the 200000 rays/s");
  ExpectRefused(R"(<sensor type="Lidar" name="Huge"><bodyRef>Top</bodyRef><rate>0.001</rate>
    <parameter name="layers">1000</parameter><parameter name="rays">1000</parameter></sensor>)",
                "name=\"Huge\"", "rays x layers = 1000000 is more than the 100000 values");
  ExpectRefused(R"(<sensor type="Imu" name="I"><bodyRef>Top</bodyRef><rate>100</rate>
    <parameter name="rays">4</parameter></sensor>)",
                "\"rays\"", "Imu sensors have no parameter 'rays'");
  ExpectRefused(R"(<sensor type="Contact" name="C"><bodyRef>Top</bodyRef><rate>10</rate>
    <parameter name="threshold">1</parameter><parameter name="threshold">2</parameter></sensor>)",
                "threshold\">2", "parameter 'threshold' is given twice");
}

// n lidars of 100 x 10 rays at 100 Hz: 100,000 rays/s each, half of what
// one sensor may cast.
std::string Lidars(int n) {
  std::string sensors;
  for (int k = 0; k < n; ++k)
    sensors += "<sensor type=\"Lidar\" name=\"L" + std::to_string(k) +
               "\"><bodyRef>Top</bodyRef><rate>100</rate><parameter name=\"rays\">100"
               "</parameter><parameter name=\"layers\">10</parameter></sensor>\n";
  return sensors;
}

// A robot's sensors together are held to one sensor's bound (the audit's
// 20 lidars each at the bound put 18.6 MB/s on the bus): refused at the
// robot, naming the sum, the largest sensors and the bound.
TEST(SensorKinds, ARobotsSensorsTogetherStayWithinTheBusBudget) {
  EXPECT_TRUE(ParseRobot(RobotWith(Lidars(2)), "two.xml").robot);  // 200,000: at the bound
  const std::string xml = RobotWith(Lidars(20));
  const RobotLoadResult result = ParseRobot(xml, "twenty.xml");
  EXPECT_FALSE(result.robot);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.line, LineOf(xml, "<robot name=\"Bot\">"));
  EXPECT_NE(d.message.find("robot 'Bot': its scanners and lidars together send 2000000 rays/s "
                           "(L0 100000, L1 100000, L2 100000 and 17 more), more than the "
                           "200000 rays/s one robot may put on the bus"),
            std::string::npos)
      << d.message;

  // Two cameras of 1280 x 720 at 15 Hz: 13.8 million pixels/s each.
  std::string cameras;
  for (const char* name : {"Left", "Right"})
    cameras += std::string("<sensor type=\"Camera\" name=\"") + name +
               "\"><bodyRef>Top</bodyRef><rate>15</rate><parameter name=\"width\">1280"
               "</parameter><parameter name=\"height\">720</parameter></sensor>\n";
  const RobotLoadResult stereo = ParseRobot(RobotWith(cameras), "stereo.xml");
  EXPECT_FALSE(stereo.robot);
  ASSERT_EQ(stereo.diagnostics.size(), 1u) << stereo.diagnostics.Format();
  EXPECT_NE(stereo.diagnostics.items()[0].message.find(
                "its cameras together send 27648000 pixels/s (Left 13824000, Right 13824000), "
                "more than the 20000000 pixels/s"),
            std::string::npos)
      << stereo.diagnostics.Format();
}

TEST(SensorKinds, UnknownKindIsRefusedByTheDtdAtItsLine) {
  const std::string xml = RobotWith(R"(<sensor type="Sonar" name="S"><bodyRef>Top</bodyRef></sensor>)");
  const RobotLoadResult result = ParseRobot(xml, "bad.xml");
  EXPECT_FALSE(result.robot);
  ASSERT_FALSE(result.diagnostics.empty());
  const Diagnostic& d = result.diagnostics.items()[0];
  EXPECT_EQ(d.line, LineOf(xml, "Sonar")) << d.message;
  EXPECT_NE(d.message.find("Sonar"), std::string::npos) << d.message;
}

TEST(SensorKinds, GeodeticOriginOutOfRangeIsRefusedAtItsLine) {
  const std::string xml = R"(<world name="W">
  <geodeticOrigin><latitude>91</latitude><longitude>0</longitude><altitude>0</altitude></geodeticOrigin>
</world>)";
  const WorldLoadResult result = ParseWorld(xml, "w.xml");
  EXPECT_FALSE(result.world);
  ASSERT_EQ(result.diagnostics.size(), 1u) << result.diagnostics.Format();
  EXPECT_EQ(result.diagnostics.items()[0].line, LineOf(xml, "<latitude>91"));
  EXPECT_NE(result.diagnostics.items()[0].message.find("latitude 91 deg is out of range"),
            std::string::npos)
      << result.diagnostics.items()[0].message;
}

}  // namespace
}  // namespace simpartner::model
