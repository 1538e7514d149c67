// simpartner-camera as a real process: a private Xvfb, a real
// simpartner-sim, real LCM multicast (udpm, ttl=0, a port per test). A red
// ball flies across a camera's view; every image must show it where the
// SIM_STATE of the image's own step has it (the pinhole projection,
// computed here from the states' poses), and a ball moving about 3 pixels a
// step tells the step apart from its neighbours. Then the sim restarts,
// and the camera renders the new simulation. Meanwhile `simpartner-cmd read`
// of the camera (in-process) prints one of those images.
#include <gtest/gtest.h>
#include <signal.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <optional>
#include <sstream>

#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/client/cmd.h"
#include "simpartner/png_image.h"
#include "simpartner/image_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/viewer/xvfb.h"

namespace simpartner::camera {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 240;
constexpr double kFov = M_PI / 3;  // 60 deg
constexpr int kPeriodSteps = 5;    // 20 Hz at 10 ms steps

// A box resting on the ground with a camera 0.9 m above its centre,
// looking along +x (camera z = x, x = z, y = -y).
constexpr const char* kRig = R"(<robot name="Rig">
  <body type="Box" name="Base"><mass>20</mass><size><x>0.4</x><y>0.2</y><z>0.4</z></size>
    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0.1</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></body>
  <sensor type="Camera" name="Eye"><bodyRef>Base</bodyRef>
    <transformation><T00>0</T00><T01>0</T01><T02>1</T02><T03>0</T03>
      <T10>0</T10><T11>-1</T11><T12>0</T12><T13>0.9</T13>
      <T20>1</T20><T21>0</T21><T22>0</T22><T23>0</T23></transformation>
    <rate>20</rate>
    <parameter name="width">320</parameter><parameter name="height">240</parameter>
    <parameter name="fov">1.0471975511965976</parameter>
    <parameter name="near">0.1</parameter><parameter name="far">50</parameter>
  </sensor>
</robot>)";

// The ball starts 4 m ahead, left of the view, and flies right at 6 m/s
// (rolling on at 4.3 m/s, 3 pixels a 10 ms step).
constexpr const char* kWorld = R"(<world name="CameraFlight">
  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>
  <surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>
  <object type="Sphere" name="Ball"><mass>1</mass><radius>0.15</radius>
    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>4</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>1.6</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>-2.0</T23></transformation>
    <translationalVelocity><vx>0</vx><vy>0</vy><vz>6</vz></translationalVelocity>
  </object>
  <robot name="Rig" file="rig.xml"/>
</world>)";

Eigen::Isometry3d Pose(const body_state_t& b) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(b.orientation[0], b.orientation[1], b.orientation[2],
                                     b.orientation[3])
                      .normalized()
                      .toRotationMatrix();
  pose.translation() = Eigen::Vector3d(b.position[0], b.position[1], b.position[2]);
  return pose;
}

// Where the ball's centre is in the image of the state `s` (pinhole of
// SPEC 9c from the rig's pose and the mount written above).
Eigen::Vector2d Projected(const state_t& s, int rig, int ball) {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  mount.translation() = Eigen::Vector3d(0, 0.9, 0);
  const Eigen::Vector3d p =
      (Pose(s.bodies[static_cast<size_t>(rig)]) * mount).inverse() *
      Eigen::Vector3d(s.bodies[static_cast<size_t>(ball)].position[0],
                      s.bodies[static_cast<size_t>(ball)].position[1],
                      s.bodies[static_cast<size_t>(ball)].position[2]);
  const double f = kWidth / 2.0 / std::tan(kFov / 2);
  return {kWidth / 2.0 + f * p.x() / p.z(), kHeight / 2.0 + f * p.y() / p.z()};
}

// Centroid of the red pixels (the ball: the sky is blue, the ground grey).
std::optional<Eigen::Vector2d> RedCentroid(const image_t& image, int* count) {
  Eigen::Vector2d sum(0, 0);
  *count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = &image.data[(static_cast<size_t>(y) * image.width + x) * 3];
      if (p[0] > 60 && p[0] - std::max(p[1], p[2]) > 40) {
        sum += Eigen::Vector2d(x + 0.5, y + 0.5);
        ++*count;
      }
    }
  if (*count == 0) return std::nullopt;
  return sum / *count;
}

TEST(CameraProcess, EachImageShowsTheStateOfItsStep) {
  const auto dir = test_support::FreshTestDir("sp_camera_process_");
  std::ofstream(dir / "rig.xml") << kRig;
  std::ofstream(dir / "world.xml") << kWorld;
  viewer::XvfbServer xvfb(640, 480, (dir / "xvfb.log").string());
  const std::string url = test_support::BusUrl(0);

  test_support::BusListener bus(url);
  model_t model;
  bool has_model = false;
  std::map<int64_t, state_t> states;
  std::vector<image_t> images;
  bus.Subscribe<model_t>(channels::kModel, [&](const model_t& m) {
    model = m;
    has_model = true;
  });
  bus.Subscribe<state_t>(channels::kState, [&](const state_t& s) { states[s.step] = s; });
  bus.Keep<image_t>(channels::kImage, &images);

  ChildProcess camera(test_support::OnDisplay(xvfb.display(),
                                              test_support::BuiltCommand(
                                                  "simpartner-camera",
                                                  {"--params", "/dev/null", "--lcm-url", url})),
                      (dir / "camera.log").string());
  ASSERT_TRUE(bus.UntilFileHolds(dir / "camera.log", "listening on", 20))
      << test_support::ReadText(dir / "camera.log");
  // simpartner-cmd read of the camera, beside the test's own listener.
  std::ostringstream read_out, read_err;
  std::future<int> read = std::async(std::launch::async, [&] {
    return client::RunCmd({"read", "Eye", "--lcm-url", url, "--timeout", "10", "--out",
                           (dir / "eye.png").string()},
                          read_out, read_err, WriteImagePng);
  });
  test_support::SimProcess sim((dir / "world.xml").string(), url, (dir / "sim.log").string(),
                               {"--stepsize=0.01", "--duration=1.2"});
  ASSERT_TRUE(bus.Until([&] { return sim.Wait(std::chrono::milliseconds(0)).has_value(); }, 30))
      << sim.Log();
  ASSERT_EQ(read.get(), 0) << read_err.str();
  bus.Until([] { return false; }, 0.5);  // the last images
  const std::vector<image_t> first = images;
  const std::map<int64_t, state_t> first_states = states;
  const model_t first_model = model;

  // The sim restarts (a new simulation): the camera follows it.
  test_support::SimProcess again((dir / "world.xml").string(), url, (dir / "sim2.log").string(),
                                 {"--stepsize=0.01", "--duration=0.3"});
  ASSERT_TRUE(bus.Until([&] { return again.Wait(std::chrono::milliseconds(0)).has_value(); }, 30))
      << again.Log();
  bus.Until([] { return false; }, 0.5);
  ASSERT_NE(model.simulation_id, first_model.simulation_id);
  int of_second = 0;
  for (size_t k = first.size(); k < images.size(); ++k)
    of_second += images[k].simulation_id == model.simulation_id;
  EXPECT_GE(of_second, 5) << "0.3 s at 20 Hz: 6 frames due";
  camera.Signal(SIGTERM);
  ASSERT_EQ(camera.Wait(std::chrono::seconds(10)), 0);
  const std::string log = test_support::ReadText(dir / "camera.log");
  ASSERT_TRUE(has_model);
  EXPECT_NE(log.find("camera 'Eye' of simulation"), std::string::npos) << log;

  int rig = -1, ball = -1;
  for (const body_t& b : first_model.bodies) {
    if (b.name == "Base") rig = b.id;
    if (b.name == "Ball") ball = b.id;
  }
  ASSERT_GE(rig, 0);
  ASSERT_GE(ball, 0);

  int checked = 0;
  for (const image_t& image : first) {
    ASSERT_EQ(image.format, image_t::FORMAT_RGB8);  // no depth asked for
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    ASSERT_EQ(image.num_bytes, kWidth * kHeight * 3);
    EXPECT_EQ(image.name, "Eye");
    EXPECT_EQ(image.robot, "Rig");
    // The first state of each period of 5 steps (the first image: the
    // first state the camera heard after the model).
    if (&image != &first.front()) {
      EXPECT_EQ(image.step % kPeriodSteps, 0) << "image of step " << image.step;
    }
    ASSERT_TRUE(first_states.count(image.step)) << "no state of step " << image.step;
    const state_t& s = first_states.at(image.step);
    EXPECT_DOUBLE_EQ(image.sim_time, s.sim_time);
    EXPECT_EQ(image.simulation_id, s.simulation_id);
    const Eigen::Vector2d expected = Projected(s, rig, ball);
    int pixels = 0;
    const auto centroid = RedCentroid(image, &pixels);
    // Only where the whole ball is in view (radius about 10 pixels).
    if (!centroid || pixels < 150 || expected.x() < 15 || expected.x() > kWidth - 15 ||
        expected.y() < 15 || expected.y() > kHeight - 15)
      continue;
    ++checked;
    EXPECT_NEAR(centroid->x(), expected.x(), 1.0) << "step " << image.step;
    EXPECT_NEAR(centroid->y(), expected.y(), 1.0) << "step " << image.step;
    // The test can tell the neighbouring steps apart.
    for (int64_t other : {image.step - 1, image.step + 1}) {
      if (first_states.count(other) == 0) continue;
      EXPECT_GT((Projected(first_states.at(other), rig, ball) - expected).norm(), 2.0);
    }
  }
  EXPECT_GE(checked, 8) << first.size() << " images; " << log;

  // The read printed an image the bus carried: its step, time and size,
  // and a mean colour (the grey ground and sky, not black).
  const std::string line = read_out.str();
  long long step = -1;
  ASSERT_EQ(std::sscanf(line.c_str(), "Eye (camera) step %lld,", &step), 1) << line;
  const auto shown = std::find_if(first.begin(), first.end(),
                                  [&](const image_t& i) { return i.step == step; });
  ASSERT_NE(shown, first.end()) << line;
  EXPECT_NE(line.find("320x240 rgb8, mean colour "), std::string::npos) << line;
  EXPECT_EQ(line.find("mean colour 0.0 0.0 0.0"), std::string::npos) << line;
  // --out wrote that image, pixel for pixel.
  EXPECT_NE(line.find("written to " + (dir / "eye.png").string()), std::string::npos) << line;
  const RgbImage file = ReadPng((dir / "eye.png").string());
  ASSERT_EQ(file.width, shown->width);
  ASSERT_EQ(file.height, shown->height);
  EXPECT_TRUE(std::equal(file.pixels.begin(), file.pixels.end(), shown->data.begin()));
  if (!HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace simpartner::camera
