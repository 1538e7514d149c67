// simpartner-camera without GL: the cameras read from SIM_MODEL, the
// viewpoint against the pinhole formula of SPEC 9c, the frame schedule and
// the depth encodings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "simpartner/camera/camera_sensor.h"

namespace simpartner::camera {
namespace {

model_t OneCameraModel(std::vector<double> params, double rate = 30) {
  model_t m{};
  m.simulation_id = 7;
  m.step_size = 0.001;
  m.num_bodies = 1;
  m.bodies.resize(1);
  m.num_robots = 1;
  m.robots.resize(1);
  m.robots[0].name = "Rig";
  sensor_t s{};
  s.name = "Eye";
  s.kind = sensor_t::KIND_CAMERA;
  s.robot = 0;
  s.body = 0;
  s.orientation[0] = 1;
  s.rate = rate;
  s.params = std::move(params);
  s.num_params = static_cast<int32_t>(s.params.size());
  m.sensors = {s};
  m.num_sensors = 1;
  return m;
}

TEST(CamerasOfModel, ReadsTheParametersAndThePeriod) {
  std::vector<std::string> problems;
  const auto cameras = CamerasOfModel(OneCameraModel({640, 480, 1.0, 0.1, 50, 2}), &problems);
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_TRUE(problems.empty());
  const CameraSensor& c = cameras[0];
  EXPECT_EQ(c.name, "Eye");
  EXPECT_EQ(c.robot, "Rig");
  EXPECT_EQ(c.width, 640);
  EXPECT_EQ(c.height, 480);
  EXPECT_EQ(c.depth, DepthFormat::kMillimetres);
  EXPECT_EQ(c.period_steps, 33);  // 1 / (30 Hz x 1 ms), rounded as the sim rounds
}

TEST(CamerasOfModel, LeavesOutABadCameraSayingWhy) {
  struct Case {
    std::vector<double> params;
    double rate;
    const char* expected;
  };
  for (const Case& c : std::vector<Case>{
           {{640, 480, 4.0, 0.1, 50, 0}, 30, "params[2] (fov) = 4 is out of range (0, pi)"},
           {{0, 480, 1.0, 0.1, 50, 0}, 30, "params[0] (width) = 0"},
           {{640, 5000, 1.0, 0.1, 50, 0}, 30, "params[1] (height) = 5000"},
           {{640, 480, 1.0, 0.5, 0.2, 0}, 30, "params[4] (far) = 0.2"},
           {{640, 480, 1.0, 0.1, 50, 3}, 30, "params[5] (depth) = 3"},
           {{640, 480, 1.0}, 30, "has 3 params"},
           {{640, 480, 1.0, 0.1, 50, 0}, 0, "rate = 0 Hz"},
       }) {
    std::vector<std::string> problems;
    EXPECT_TRUE(CamerasOfModel(OneCameraModel(c.params, c.rate), &problems).empty());
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_NE(problems[0].find("sensors[0] (camera 'Eye'): "), std::string::npos) << problems[0];
    EXPECT_NE(problems[0].find(c.expected), std::string::npos) << problems[0];
  }
}

// A camera on a body turned and moved, looking at a world point: the
// viewpoint's matrices put it at u = cx + f x / z, v = cy + f y / z.
TEST(CameraViewpoint, ProjectsAsThePinhole) {
  CameraSensor c;
  c.width = 640;
  c.height = 400;
  c.fov = 70 * M_PI / 180;
  c.near = 0.1;
  c.far = 100;
  c.mount = Eigen::Translation3d(0.1, 0.5, 0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
  const Eigen::Isometry3d body(Eigen::Translation3d(1, 2, 3) *
                               Eigen::AngleAxisd(-0.4, Eigen::Vector3d(1, 1, 0).normalized()));
  const viewer::Viewpoint v = CameraViewpoint(c, body);
  const Eigen::Isometry3d camera_pose = body * c.mount;
  const double f = (c.width / 2.0) / std::tan(c.fov / 2);
  EXPECT_DOUBLE_EQ(FocalPixels(c), f);
  for (const Eigen::Vector3d& in_camera :
       {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(1.2, -0.7, 4), Eigen::Vector3d(-0.3, 0.9, 2.5)}) {
    const Eigen::Vector3d world = camera_pose * in_camera;
    const Eigen::Vector4d clip = v.projection * v.view * world.homogeneous();
    const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
    const double u = (ndc.x() + 1) / 2 * c.width, vv = (1 - ndc.y()) / 2 * c.height;
    EXPECT_NEAR(u, c.width / 2.0 + f * in_camera.x() / in_camera.z(), 1e-9);
    EXPECT_NEAR(vv, c.height / 2.0 + f * in_camera.y() / in_camera.z(), 1e-9);
  }
  EXPECT_TRUE(v.eye.isApprox(camera_pose.translation()));
}

TEST(FrameSchedule, RendersTheFirstStateOfEachPeriodAndCountsWhatWasDue) {
  FrameSchedule s(10);
  EXPECT_TRUE(s.Due(0));
  EXPECT_FALSE(s.Due(1));
  EXPECT_FALSE(s.Due(9));
  EXPECT_TRUE(s.Due(10));
  EXPECT_TRUE(s.Due(43));  // 20 and 30 were lost: due, not rendered
  EXPECT_EQ(s.due(), 5);
  EXPECT_FALSE(s.Due(45));
  EXPECT_TRUE(s.Due(3));   // a reset
  EXPECT_EQ(s.due(), 6);
}

TEST(Depth, MetresAndMillimetresFromTheDepthBuffer) {
  const double near = 0.1, far = 50;
  // The buffer value gluPerspective gives a point at distance d.
  auto buffer = [&](double d) {
    const double ndc = (far + near) / (far - near) - 2 * far * near / ((far - near) * d);
    return static_cast<float>((ndc + 1) / 2);
  };
  for (double d : {0.1, 1.0, 3.7, 49.0}) EXPECT_NEAR(DepthMetres(buffer(d), near, far), d, 1e-3 * d);
  EXPECT_TRUE(std::isinf(DepthMetres(1.0f, near, far)));
  EXPECT_EQ(DepthMillimetres(3.7004f), 3700);
  EXPECT_EQ(DepthMillimetres(std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(DepthMillimetres(70.0f), 0);  // beyond 65.535 m

  CameraSensor c;
  c.near = near;
  c.far = far;
  c.depth = DepthFormat::kMillimetres;
  const std::vector<uint8_t> mm = DepthBytes({buffer(2.5), 1.0f}, c);
  ASSERT_EQ(mm.size(), 4u);
  EXPECT_EQ(mm[0] | mm[1] << 8, 2500);  // little-endian
  EXPECT_EQ(mm[2] | mm[3] << 8, 0);
  c.depth = DepthFormat::kMetres;
  const std::vector<uint8_t> m = DepthBytes({buffer(2.5)}, c);
  ASSERT_EQ(m.size(), 4u);
  float metres = 0;
  std::memcpy(&metres, m.data(), 4);
  EXPECT_NEAR(metres, 2.5, 1e-3);
}

}  // namespace
}  // namespace simpartner::camera
