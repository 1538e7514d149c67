// The field sensor kinds against closed forms, on both engines: an
// IMU at rest reads g up, in free fall 0, on a turntable omega and
// omega^2 r; noise statistics match the configured densities; encoders
// count floor(angle cpr / 2 pi); GNSS reads the local position and its
// latitude; a lidar reads a wall and the floor at each layer's elevation;
// a contact sensor tells the ground from the air. Readings repeat bit for
// bit for a seed, whatever else is read.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "simpartner/model/sensor_parameters.h"
#include "simpartner/sim/geodetic.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

using testing::Command;
using testing::MakeSim;
using testing::Transform;
using testing::Vec;

constexpr double kG = 9.81;

// Rotation about y by +90 degrees with a translation: sensor z along world
// +x, sensor y up (the gen3 Scanner's mount).
std::string FacingX(double x, double y, double z) {
  auto n = [](double v) { return std::to_string(v); };
  return "<transformation><T00>0</T00><T01>0</T01><T02>1</T02><T03>" + n(x) +
         "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" + n(y) +
         "</T13><T20>-1</T20><T21>0</T21><T22>0</T22><T23>" + n(z) + "</T23></transformation>";
}

std::string ParameterXml(const std::vector<std::pair<std::string, double>>& values) {
  std::string out;
  for (const auto& [name, value] : values)
    out += "<parameter name=\"" + name + "\">" + std::to_string(value) + "</parameter>";
  return out;
}

// A robot of one 0.2 m, 2 kg box at `at` carrying `sensors` (on "Box").
std::string BoxRobot(const std::string& sensors, double x, double y, double z) {
  return "<robot name=\"BoxBot\"><body type=\"Box\" name=\"Box\"><mass>2</mass>" +
         Vec("size", 0.2, 0.2, 0.2) + Transform(x, y, z) + "</body>" + sensors + "</robot>";
}

std::string World(double gravity, bool ground, const std::string& extra = "") {
  return "<world name=\"S\">" + Vec("gravity", 0, gravity, 0) +
         "<geodeticOrigin><latitude>60.1867</latitude><longitude>24.8283</longitude>"
         "<altitude>20</altitude></geodeticOrigin>" +
         (ground ? "<surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>" : "") + extra +
         "<robot name=\"Bot\" file=\"bot.xml\"/></world>";
}

class Sensors : public ::testing::TestWithParam<const char*> {
 protected:
  simpartner::Parameters Params(double stepsize = 0.001, int seed = 0) const {
    simpartner::Parameters params;
    params.engine = GetParam();
    params.stepsize = stepsize;
    params.sensorSeed = seed;
    return params;
  }
  std::unique_ptr<Simulation> Sim(const std::string& world, const std::string& robot,
                                  const simpartner::Parameters& params) const {
    return MakeSim(world, {{"bot.xml", robot}}, params);
  }
};
INSTANTIATE_TEST_SUITE_P(Engines, Sensors, ::testing::Values("ode", "mujoco"));

// The readings of sensor `name` over `steps` steps.
std::vector<std::vector<double>> Readings(Simulation* sim, int steps, const std::string& name) {
  std::vector<std::vector<double>> out;
  for (int n = 0; n < steps; ++n) {
    EXPECT_TRUE(sim->Step());
    for (const sensor_reading_t& r : sim->TakeSensorReadings())
      if (r.name == name) out.push_back(r.values);
  }
  return out;
}

struct Stats {
  double mean = 0, std = 0;
};
Stats Of(const std::vector<std::vector<double>>& readings, size_t k) {
  Stats s;
  for (const auto& r : readings) s.mean += r[k];
  s.mean /= static_cast<double>(readings.size());
  for (const auto& r : readings) s.std += (r[k] - s.mean) * (r[k] - s.mean);
  s.std = std::sqrt(s.std / static_cast<double>(readings.size() - 1));
  return s;
}

// Sample mean and standard deviation of N normal samples within five of
// their standard errors (sigma / sqrt N and sigma / sqrt 2N).
void ExpectNormal(const Stats& s, double mean, double sigma, size_t n, const std::string& what) {
  EXPECT_NEAR(s.mean, mean, 5 * sigma / std::sqrt(static_cast<double>(n))) << what;
  EXPECT_NEAR(s.std, sigma, 5 * sigma / std::sqrt(2.0 * static_cast<double>(n))) << what;
}

const char* kImu100 = "<sensor type=\"Imu\" name=\"Imu\"><bodyRef>Box</bodyRef><rate>100</rate>";

TEST_P(Sensors, ImuAtRestReadsGravityUpInItsOwnFrame) {
  // Mounted turned 90 degrees about z (sensor x = world y): up is sensor +x.
  const std::string mount =
      "<transformation><T00>0</T00><T01>-1</T01><T02>0</T02><T03>0</T03>"
      "<T10>1</T10><T11>0</T11><T12>0</T12><T13>0</T13>"
      "<T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation>";
  const std::string robot = BoxRobot(
      "<sensor type=\"Imu\" name=\"Imu\"><bodyRef>Box</bodyRef>" + mount + "<rate>100</rate></sensor>",
      0, 0.1, 0);
  auto sim = Sim(World(-kG, true), robot, Params());
  const auto readings = Readings(sim.get(), 2000, "Imu");
  ASSERT_EQ(readings.size(), 200u);
  const std::vector<double>& r = readings.back();
  ASSERT_EQ(r.size(), 10u);
  EXPECT_NEAR(r[0], kG, 1e-3);
  EXPECT_NEAR(r[1], 0.0, 1e-3);
  EXPECT_NEAR(r[2], 0.0, 1e-3);
  for (int k = 3; k < 6; ++k) EXPECT_NEAR(r[k], 0.0, 1e-3) << k;
  // Orientation: the mount's, 90 degrees about z.
  EXPECT_NEAR(r[6], std::cos(M_PI / 4), 1e-3);
  EXPECT_NEAR(r[9], std::sin(M_PI / 4), 1e-3);
}

TEST_P(Sensors, ImuInFreeFallReadsZero) {
  auto sim = Sim(World(-kG, false), BoxRobot(std::string(kImu100) + "</sensor>", 0, 100, 0),
                 Params());
  const auto readings = Readings(sim.get(), 500, "Imu");
  ASSERT_EQ(readings.size(), 50u);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(readings.back()[k], 0.0, 1e-6) << k;
}

// A 1000 kg base on the ground and a 1 kg table on a hinge about y, driven
// at omega; an IMU on the table at radius r along its x axis, an encoder
// on the hinge.
std::string Turntable(double r, double cpr) {
  return R"(<robot name="Turntable">
  <body type="Box" name="Base"><mass>1000</mass>)" + Vec("size", 1, 1, 1) + Transform(0, 0.5, 0) +
         R"(</body><body type="Box" name="Table"><mass>1</mass>)" + Vec("size", 2, 0.1, 2) +
         Transform(0, 1.05, 0) + R"(</body>
  <joint type="Hinge" name="Spindle"><body1>Table</body1><body2>Base</body2>)" +
         Vec("anchor", 0, 1, 0) + Vec("axis1", 0, 1, 0) + R"(</joint>
  <sensor type="Imu" name="Imu"><bodyRef>Table</bodyRef>)" + Transform(r, 0, 0) +
         R"(<rate>100</rate></sensor>
  <sensor type="Encoder" name="Encoder"><jointRef>Spindle</jointRef><rate>100</rate>)" +
         ParameterXml({{"countsPerRevolution", cpr}}) + R"(</sensor>
  <actuator type="JointController" name="TableMotor"><jointRef>Spindle</jointRef></actuator>
</robot>)";
}

TEST_P(Sensors, ImuOnATurntableReadsOmegaAndTheCentripetalAcceleration) {
  const double omega = 2.0, r = 0.8;
  auto sim = Sim(World(-kG, true), Turntable(r, 1024), Params());
  ASSERT_FALSE(sim->Submit(Command("TableMotor", command_t::ACTION_SET, {1000, omega})));
  const auto readings = Readings(sim.get(), 2000, "Imu");
  const std::vector<double>& last = readings.back();
  // The table's y axis is the spin axis; the IMU at +x is pulled to -x.
  EXPECT_NEAR(last[4], omega, 1e-3 * omega);
  EXPECT_NEAR(last[3], 0.0, 1e-3);
  EXPECT_NEAR(last[5], 0.0, 1e-3);
  EXPECT_NEAR(last[0], -omega * omega * r, 0.01 * omega * omega * r);
  EXPECT_NEAR(last[1], kG, 0.01);
  EXPECT_NEAR(last[2], 0.0, 0.01 * omega * omega * r);
}

TEST_P(Sensors, EncoderCountsTheJointAngleThroughSeveralTurns) {
  const double omega = 2.0, cpr = 500;
  auto sim = Sim(World(-kG, true), Turntable(0.5, cpr), Params());
  ASSERT_FALSE(sim->Submit(Command("TableMotor", command_t::ACTION_SET, {1000, omega})));
  const int spindle = 0;
  int checked = 0;
  double angle = 0;
  for (int n = 0; n < 12000; ++n) {
    ASSERT_TRUE(sim->Step());
    for (const sensor_reading_t& reading : sim->TakeSensorReadings()) {
      if (reading.name != "Encoder") continue;
      state_t state;
      sim->FillState(&state);
      angle = state.joints[spindle].continuous_position[0];
      ASSERT_EQ(reading.values.size(), 2u);
      EXPECT_EQ(reading.values[0], std::floor(angle * cpr / (2 * M_PI))) << "step " << n;
      EXPECT_NEAR(reading.values[1], state.joints[spindle].rate[0] * cpr / (2 * M_PI), 1e-9);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 1200);
  // 12 s at 2 rad/s: nearly four turns, counted on without wrapping.
  EXPECT_GT(std::abs(angle), 3.5 * 2 * M_PI);
}

// Zero gravity, nothing to touch: the box floats still, so every reading
// is bias plus noise around an exact truth.
TEST_P(Sensors, ImuNoiseMatchesItsDensityAndBiasOver10000Samples) {
  const double accel_density = 0.002, gyro_density = 0.0005, rate = 100;
  const std::string robot = BoxRobot(std::string(kImu100) +
      ParameterXml({{"accelNoiseDensity", accel_density}, {"accelBiasX", 0.05},
                  {"gyroNoiseDensity", gyro_density}, {"gyroBiasZ", -0.003}}) + "</sensor>",
      0, 1, 0);
  auto sim = Sim(World(0, false), robot, Params(0.01, 7));
  const auto readings = Readings(sim.get(), 10000, "Imu");
  ASSERT_EQ(readings.size(), 10000u);
  const double accel_sigma = accel_density * std::sqrt(rate);  // 0.02 m/s^2
  const double gyro_sigma = gyro_density * std::sqrt(rate);    // 0.005 rad/s
  ExpectNormal(Of(readings, 0), 0.05, accel_sigma, readings.size(), "ax");
  ExpectNormal(Of(readings, 1), 0.0, accel_sigma, readings.size(), "ay");
  ExpectNormal(Of(readings, 2), 0.0, accel_sigma, readings.size(), "az");
  ExpectNormal(Of(readings, 3), 0.0, gyro_sigma, readings.size(), "wx");
  ExpectNormal(Of(readings, 5), -0.003, gyro_sigma, readings.size(), "wz");
}

// With only a bias random walk of density q, successive samples at f Hz
// differ by a normal step of q sqrt(1/f).
TEST_P(Sensors, ImuBiasRandomWalkGrowsAsItsDensity) {
  const double q = 0.01, rate = 100;
  const std::string robot = BoxRobot(
      std::string(kImu100) + ParameterXml({{"gyroBiasRandomWalk", q}}) + "</sensor>", 0, 1, 0);
  auto sim = Sim(World(0, false), robot, Params(0.001, 3));
  const auto readings = Readings(sim.get(), 100000, "Imu");
  ASSERT_EQ(readings.size(), 10000u);
  std::vector<std::vector<double>> steps;
  for (size_t k = 1; k < readings.size(); ++k) steps.push_back({readings[k][4] - readings[k - 1][4]});
  ExpectNormal(Of(steps, 0), 0.0, q * std::sqrt(1.0 / rate), steps.size(), "walk");
}

TEST_P(Sensors, SameSeedSameReadingsWhateverIsReadBetween) {
  const std::string robot = BoxRobot(
      std::string(kImu100) + ParameterXml({{"accelNoiseDensity", 0.01}, {"gyroBiasRandomWalk", 0.1}}) +
          "</sensor><sensor type=\"Gnss\" name=\"Gnss\"><bodyRef>Box</bodyRef><rate>10</rate>" +
          ParameterXml({{"horizontalNoise", 2}}) + "</sensor>",
      0, 1, 0);
  auto first = Sim(World(-kG, true), robot, Params(0.001, 42));
  auto second = Sim(World(-kG, true), robot, Params(0.001, 42));
  auto other = Sim(World(-kG, true), robot, Params(0.001, 43));
  std::vector<std::vector<double>> a, b, c;
  for (int n = 0; n < 300; ++n) {
    // The second sim is also asked for readings at every step.
    ASSERT_FALSE(second->Submit(Command("Imu", command_t::ACTION_READ, {})));
    ASSERT_FALSE(second->Submit(Command("Gnss", command_t::ACTION_READ, {})));
    ASSERT_TRUE(first->Step() && second->Step() && other->Step());
    for (const sensor_reading_t& r : first->TakeSensorReadings()) a.push_back(r.values);
    const std::vector<sensor_reading_t> rs = second->TakeSensorReadings();
    for (size_t k = 0; k + 2 < rs.size(); ++k) b.push_back(rs[k].values);  // the periodic ones
    for (const sensor_reading_t& r : other->TakeSensorReadings()) c.push_back(r.values);
  }
  ASSERT_EQ(a.size(), 33u);
  EXPECT_EQ(a, b);  // bit for bit
  EXPECT_NE(a, c);
}

// The floating box at (3, 2, -4) of a y-up world: east 3, north 4, up 2.
TEST_P(Sensors, GnssMeanConvergesToTheTruthAndItsLatitude) {
  const double h = 0.5, v = 1.0, velocity = 0.1;
  const std::string robot =
      BoxRobot("<sensor type=\"Gnss\" name=\"Gnss\"><bodyRef>Box</bodyRef><rate>100</rate>" +
                   ParameterXml({{"horizontalNoise", h}, {"verticalNoise", v},
                               {"velocityNoise", velocity}}) + "</sensor>",
               3, 2, -4);
  auto sim = Sim(World(0, false), robot, Params(0.01, 11));
  const auto readings = Readings(sim.get(), 10000, "Gnss");
  ASSERT_EQ(readings.size(), 10000u);
  ASSERT_EQ(readings[0].size(), 10u);
  EXPECT_EQ(Of(readings, 0).mean, 1.0);
  ExpectNormal(Of(readings, 1), 3.0, h, readings.size(), "east");
  ExpectNormal(Of(readings, 2), 4.0, h, readings.size(), "north");
  ExpectNormal(Of(readings, 3), 2.0, v, readings.size(), "up");
  ExpectNormal(Of(readings, 4), 0.0, velocity, readings.size(), "v east");
  // Latitude and longitude of the mean position by the ellipsoid's radii
  // of curvature at the origin: meridian M, prime vertical N.
  const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
  const double phi = 60.1867 * M_PI / 180, s2 = std::sin(phi) * std::sin(phi);
  const double meridian = a * (1 - e2) / std::pow(1 - e2 * s2, 1.5);
  const double prime = a / std::sqrt(1 - e2 * s2);
  const Stats north = Of(readings, 2), east = Of(readings, 1);
  EXPECT_NEAR(Of(readings, 7).mean, 60.1867 + north.mean / meridian * 180 / M_PI, 1e-9);
  EXPECT_NEAR(Of(readings, 8).mean,
              24.8283 + east.mean / (prime * std::cos(phi)) * 180 / M_PI, 1e-9);
  // The ellipsoid falls away under a horizontal offset d by d^2 / 2R.
  const double drop = east.mean * east.mean / (2 * prime) + north.mean * north.mean / (2 * meridian);
  EXPECT_NEAR(Of(readings, 9).mean, 20.0 + Of(readings, 3).mean + drop, 1e-7);
}

TEST_P(Sensors, GnssLosesItsFixUnderCover) {
  const std::string gnss =
      "<sensor type=\"Gnss\" name=\"Gnss\"><bodyRef>Box</bodyRef><rate>100</rate>" +
      ParameterXml({{"coverHeight", 50}}) + "</sensor>";
  const std::string roof = "<object type=\"Box\" name=\"Roof\" static=\"true\">" +
                           Vec("size", 4, 0.2, 4) + Transform(0, 5, 0) + "</object>";
  auto open = Sim(World(0, false), BoxRobot(gnss, 0, 1, 0), Params());
  auto covered = Sim(World(0, false, roof), BoxRobot(gnss, 0, 1, 0), Params());
  EXPECT_EQ(Readings(open.get(), 10, "Gnss").back()[0], 1.0);
  const std::vector<double> r = Readings(covered.get(), 10, "Gnss").back();
  EXPECT_EQ(r, std::vector<double>(10, 0.0));  // no fix, and nothing else
}

TEST(Geodetic, EnuToGeodeticAgreesWithTheRadiiOfCurvatureAndTheFrame) {
  const model::GeodeticOrigin origin{60.1867, 24.8283, 20.0, {}};
  const Eigen::Vector3d at_origin = EnuToGeodetic(origin, Eigen::Vector3d::Zero());
  EXPECT_NEAR(at_origin.x(), 60.1867, 1e-12);
  EXPECT_NEAR(at_origin.y(), 24.8283, 1e-12);
  EXPECT_NEAR(at_origin.z(), 20.0, 1e-8);
  // 1 km up is 1 km higher, same place.
  const Eigen::Vector3d up = EnuToGeodetic(origin, Eigen::Vector3d(0, 0, 1000));
  EXPECT_NEAR(up.z(), 1020.0, 1e-6);
  EXPECT_NEAR(up.x(), 60.1867, 1e-12);
  const LocalFrame frame = LocalFrameOf(Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(frame.east, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(frame.north, Eigen::Vector3d(0, 0, -1));
  const LocalFrame z_up = LocalFrameOf(Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(z_up.north, Eigen::Vector3d(0, 1, 0));
}

// A lidar at the origin facing +x (sensor y up), a wall whose face is at
// x = D: a ray at azimuth a and elevation e travels D / (cos e cos a).
TEST_P(Sensors, LidarReadsAWallInEveryLayer) {
  const double D = 4.0, half_span = 0.4, lowest = -0.3, highest = 0.3;
  const int rays = 7, layers = 5;
  const std::string lidar =
      "<sensor type=\"Lidar\" name=\"Lidar\"><bodyRef>Box</bodyRef>" + FacingX(0, 0, 0) +
      "<rate>100</rate>" +
      ParameterXml({{"rays", rays}, {"halfSpan", half_span}, {"layers", layers},
                  {"lowestElevation", lowest}, {"highestElevation", highest}, {"range", 30}}) +
      "</sensor>";
  const std::string wall = "<object type=\"Box\" name=\"Wall\" static=\"true\">" +
                           Vec("size", 0.2, 40, 40) + Transform(D + 0.1, 0, 0) + "</object>";
  auto sim = Sim(World(0, false, wall), BoxRobot(lidar, 0, 0, 0), Params());
  const std::vector<double> r = Readings(sim.get(), 10, "Lidar").back();
  ASSERT_EQ(r.size(), static_cast<size_t>(rays * layers));
  for (int layer = 0; layer < layers; ++layer) {
    const double e = lowest + (highest - lowest) * layer / (layers - 1);
    for (int k = 0; k < rays; ++k) {
      const double a = -half_span + 2 * half_span * k / (rays - 1);
      EXPECT_NEAR(r[static_cast<size_t>(layer * rays + k)], D / (std::cos(e) * std::cos(a)), 1e-6)
          << "layer " << layer << " ray " << k;
    }
  }
}

// A level lidar 1 m above the floor: a layer at elevation e < 0 meets the
// floor at 1 / sin(-e) on every ray; a layer looking up has no return.
TEST_P(Sensors, LidarLayerElevationsByTheirFloorDistance) {
  const double height = 1.0, range = 20.0;
  const std::vector<double> elevation = {-0.6, -0.35, -0.1, 0.15};
  const std::string lidar =
      "<sensor type=\"Lidar\" name=\"Lidar\"><bodyRef>Box</bodyRef>" + FacingX(0, 0, 0) +
      "<rate>100</rate>" +
      ParameterXml({{"rays", 9}, {"halfSpan", 3.0}, {"layers", 4}, {"lowestElevation", -0.6},
                  {"highestElevation", 0.15}, {"range", range}}) +
      "</sensor>";
  auto sim = Sim(World(0, true), BoxRobot(lidar, 0, height, 0), Params());
  const std::vector<double> r = Readings(sim.get(), 10, "Lidar").back();
  ASSERT_EQ(r.size(), 36u);
  for (size_t layer = 0; layer < 4; ++layer) {
    for (size_t k = 0; k < 9; ++k) {
      const double expected = elevation[layer] < 0 ? height / std::sin(-elevation[layer]) : range;
      EXPECT_NEAR(r[layer * 9 + k], expected, 1e-6) << "layer " << layer << " ray " << k;
    }
  }
}

TEST_P(Sensors, LidarMinRangeDropoutAndRangeNoise) {
  const double D = 2.0;
  const std::string wall = "<object type=\"Box\" name=\"Wall\" static=\"true\">" +
                           Vec("size", 0.2, 40, 40) + Transform(D + 0.1, 0, 0) + "</object>";
  auto lidar = [](const std::vector<std::pair<std::string, double>>& extra) {
    std::vector<std::pair<std::string, double>> p = {
        {"rays", 1}, {"layers", 1}, {"lowestElevation", 0}, {"highestElevation", 0}, {"range", 10}};
    p.insert(p.end(), extra.begin(), extra.end());
    return "<sensor type=\"Lidar\" name=\"Lidar\"><bodyRef>Box</bodyRef>" + FacingX(0, 0, 0) +
           "<rate>100</rate>" + ParameterXml(p) + "</sensor>";
  };
  // The wall nearer than minRange: no return (max range).
  auto blind = Sim(World(0, false, wall), BoxRobot(lidar({{"minRange", 3}}), 0, 0, 0), Params());
  EXPECT_EQ(Readings(blind.get(), 10, "Lidar").back()[0], 10.0);
  // Range noise of sigma 0.05 and half the rays dropped, over 10000 samples.
  auto noisy = Sim(World(0, false, wall),
                   BoxRobot(lidar({{"rangeNoise", 0.05}, {"dropout", 0.5}}), 0, 0, 0),
                   Params(0.01, 5));
  const auto readings = Readings(noisy.get(), 10000, "Lidar");
  std::vector<std::vector<double>> returns;
  for (const auto& r : readings)
    if (r[0] != 10.0) returns.push_back(r);
  const double n = static_cast<double>(readings.size());
  EXPECT_NEAR(static_cast<double>(returns.size()) / n, 0.5, 5 * std::sqrt(0.25 / n));
  ExpectNormal(Of(returns, 0), D, 0.05, returns.size(), "range");
}

TEST_P(Sensors, ContactSensorTellsTheGroundFromTheAir) {
  const std::string contact =
      "<sensor type=\"Contact\" name=\"Bumper\"><bodyRef>Box</bodyRef><rate>100</rate></sensor>";
  auto resting = Sim(World(-kG, true), BoxRobot(contact, 0, 0.1, 0), Params());
  auto falling = Sim(World(-kG, true), BoxRobot(contact, 0, 50, 0), Params());
  const std::vector<double> on_ground = Readings(resting.get(), 1000, "Bumper").back();
  ASSERT_EQ(on_ground.size(), 5u);
  EXPECT_EQ(on_ground[0], 1.0);
  EXPECT_NEAR(on_ground[1], 2 * kG, 0.01 * 2 * kG);  // its weight
  EXPECT_NEAR(on_ground[3], 2 * kG, 0.01 * 2 * kG);  // pushing up
  const std::vector<double> in_air = Readings(falling.get(), 1000, "Bumper").back();
  EXPECT_EQ(in_air[0], 0.0);
  EXPECT_EQ(in_air[1], 0.0);
}

// The shipped gen3 with its field sensors reading at their rates moves
// exactly as without them: sensors never touch the physics.
TEST_P(Sensors, ShippedSensorsLeaveTheTrajectoryBitForBit) {
  const model::World with =
      model::LoadWorldOrThrow(std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml");
  model::World without = with;
  for (model::RobotInstance& r : without.robots) {
    std::vector<model::Sensor> kept;
    for (const model::Sensor& s : r.robot.sensors)
      if (!model::NeedsRate(s.kind)) kept.push_back(s);
    ASSERT_EQ(r.robot.sensors.size(), kept.size() + 7) << "Imu, Gnss, 4 encoders, Lidar";
    r.robot.sensors = kept;
  }
  Simulation a(with, Params(), 1), b(without, Params(), 1);
  for (const char* motor : {"Axle1Motor", "Axle2Motor", "Axle3Motor", "Axle4Motor"}) {
    ASSERT_FALSE(a.Submit(Command(motor, command_t::ACTION_SET, {1000, 1.0})));
    ASSERT_FALSE(b.Submit(Command(motor, command_t::ACTION_SET, {1000, 1.0})));
  }
  size_t readings = 0;
  for (int n = 0; n < 1000; ++n) {
    ASSERT_TRUE(a.Step() && b.Step());
    readings += a.TakeSensorReadings().size();
  }
  EXPECT_EQ(readings, 10u * (10 + 1 + 4 * 10) + 12u);  // 100 Hz x5, 10 Hz, 12.5 Hz over 1 s
  state_t sa, sb;
  a.FillState(&sa);
  b.FillState(&sb);
  for (size_t i = 0; i < sa.bodies.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(sa.bodies[i].position[k], sb.bodies[i].position[k]) << "body " << i;
}

// A program that steps without taking the readings keeps a bounded number
// of them, the newest.
TEST_P(Sensors, UntakenReadingsAreBounded) {
  const std::string imu =
      "<sensor type=\"Imu\" name=\"Imu\"><bodyRef>Box</bodyRef><rate>1000</rate></sensor>";
  auto sim = Sim(World(0, false), BoxRobot(imu, 0, 1, 0), Params());
  for (int n = 0; n < 10000; ++n) ASSERT_TRUE(sim->Step());
  const std::vector<sensor_reading_t> readings = sim->TakeSensorReadings();
  EXPECT_LE(readings.size(), Simulation::kMaxUntakenReadings);
  EXPECT_GE(readings.size(), Simulation::kMaxUntakenReadings / 2);
  EXPECT_EQ(readings.back().step, 10000);
}

// Rate 0 (SENSOR_PARAMS) stops the readings at a rate; a READ still gets
// one, with the noise of the file's rate.
TEST_P(Sensors, RateZeroReadsOnRequestOnly) {
  const std::string robot = BoxRobot(
      std::string(kImu100) + ParameterXml({{"accelNoiseDensity", 0.002}}) + "</sensor>", 0, 1, 0);
  auto sim = Sim(World(0, false), robot, Params(0.01, 9));
  ASSERT_FALSE(sim->Submit(Command("Imu", command_t::ACTION_SENSOR_PARAMS, {0})));
  EXPECT_TRUE(Readings(sim.get(), 100, "Imu").empty());
  std::vector<std::vector<double>> requested;
  for (int n = 0; n < 10000; ++n) {
    ASSERT_FALSE(sim->Submit(Command("Imu", command_t::ACTION_READ, {})));
    const auto r = Readings(sim.get(), 1, "Imu");
    requested.insert(requested.end(), r.begin(), r.end());
  }
  ASSERT_EQ(requested.size(), 10000u);
  ExpectNormal(Of(requested, 0), 0.0, 0.002 * std::sqrt(100.0), requested.size(), "ax");
}

}  // namespace
}  // namespace simpartner::sim
