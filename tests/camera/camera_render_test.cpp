// simpartner-camera's offscreen rendering under a private Xvfb (llvmpipe):
// a camera on a robot, looking along the world's +x, sees a plate at a
// known pose where the pinhole formula (computed here from the poses and
// the field of view, not by the renderer's matrices) puts it, and a wall at
// a known distance at that depth. The model comes from robot and world XML
// through the model loader, and SIM_MODEL from the sim library in process.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "../support/test_dir.h"
#include "simpartner/camera/camera_sensor.h"
#include "simpartner/camera/offscreen.h"
#include "simpartner/model/loader.h"
#include "simpartner/sim/simulation.h"
#include "simpartner/viewer/gl_window.h"
#include "simpartner/viewer/xvfb.h"

namespace simpartner::camera {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 240;
constexpr double kFovDeg = 60;

// A one-body robot whose camera sits 1 m above the body's origin and looks
// along the body's +x (camera z = x, camera x = z, camera y = -y).
std::string RigRobot(const std::string& depth) {
  return R"(<robot name="Rig">
  <body type="Box" name="Base"><mass>10</mass><size><x>0.2</x><y>0.2</y><z>0.2</z></size>
    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>0</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></body>
  <sensor type="Camera" name="Eye"><bodyRef>Base</bodyRef>
    <transformation>
      <T00>0</T00><T01>0</T01><T02>1</T02><T03>0</T03>
      <T10>0</T10><T11>-1</T11><T12>0</T12><T13>1</T13>
      <T20>1</T20><T21>0</T21><T22>0</T22><T23>0</T23>
    </transformation>
    <rate>30</rate>
    <parameter name="width">)" + std::to_string(kWidth) + R"(</parameter>
    <parameter name="height">)" + std::to_string(kHeight) + R"(</parameter>
    <parameter name="fov">)" + std::to_string(kFovDeg * M_PI / 180) + R"(</parameter>
    <parameter name="near">0.1</parameter>
    <parameter name="far">30</parameter>
    <parameter name="depth">)" + depth + R"(</parameter>
  </sensor>
</robot>)";
}

std::string Box(const std::string& name, const Eigen::Vector3d& size, const Eigen::Vector3d& at) {
  std::ostringstream x;
  x << "<object type=\"Box\" name=\"" << name << "\" static=\"true\"><size><x>" << size.x()
    << "</x><y>" << size.y() << "</y><z>" << size.z() << "</z></size><transformation>"
    << "<T00>1</T00><T01>0</T01><T02>0</T02><T03>" << at.x() << "</T03>"
    << "<T10>0</T10><T11>1</T11><T12>0</T12><T13>" << at.y() << "</T13>"
    << "<T20>0</T20><T21>0</T21><T22>1</T22><T23>" << at.z() << "</T23></transformation></object>";
  return x.str();
}

// No ground: the sky is behind everything but the objects.
std::string World(const std::string& objects) {
  return R"(<world name="CameraTest"><gravity><x>0</x><y>-9.81</y><z>0</z></gravity>)" + objects +
         R"(<robot name="Rig" file="rig.xml"/></world>)";
}

class CameraRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test_support::FreshTestDir("sp_camera_render_");
    xvfb_ = std::make_unique<viewer::XvfbServer>(640, 480, (dir_ / "xvfb.log").string());
    setenv("DISPLAY", xvfb_->display().c_str(), 1);
    window_ = std::make_unique<viewer::GlWindow>("camera test", 64, 64, false, true);
    offscreen_ = std::make_unique<OffscreenRenderer>();
  }
  void TearDown() override {
    offscreen_.reset();
    window_.reset();
    xvfb_.reset();
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }

  // The scene of the world, and its one camera.
  CameraSensor Load(const std::string& objects, const std::string& depth) {
    std::ofstream(dir_ / "rig.xml") << RigRobot(depth);
    std::ofstream(dir_ / "world.xml") << World(objects);
    const model::WorldLoadResult loaded = model::LoadWorldFile((dir_ / "world.xml").string());
    if (!loaded.world) throw std::runtime_error(loaded.diagnostics.Format());
    // SIM_MODEL as the sim fills it (the test, not the camera, links the sim).
    sim::Simulation simulation(*loaded.world, Parameters(), 1);
    model_t m;
    simulation.FillModel(&m);
    EXPECT_TRUE(scene_.OfferModel(m).accepted);
    std::vector<std::string> problems;
    const std::vector<CameraSensor> cameras = CamerasOfModel(m, &problems);
    EXPECT_TRUE(problems.empty()) << problems.front();
    EXPECT_EQ(cameras.size(), 1u);
    return cameras.at(0);
  }

  std::filesystem::path dir_;
  std::unique_ptr<viewer::XvfbServer> xvfb_;
  std::unique_ptr<viewer::GlWindow> window_;
  std::unique_ptr<OffscreenRenderer> offscreen_;
  viewer::Scene scene_;
};

bool IsSky(const viewer::RgbImage::Rgb& p) {
  const std::array<float, 3> sky = viewer::SkyColor();
  return std::abs(p.r - sky[0] * 255) < 3 && std::abs(p.g - sky[1] * 255) < 3 &&
         std::abs(p.b - sky[2] * 255) < 3;
}

// A thin plate facing the camera, off the optical axis: its pixels'
// centroid is the pinhole projection of its centre, its width f w / z.
TEST_F(CameraRenderTest, PlateCentroidIsWhereThePinholePutsIt) {
  const Eigen::Vector3d centre(5.0, 1.4, 0.8);  // world; the camera is at (0, 1, 0)
  const Eigen::Vector3d size(0.01, 0.4, 0.6);   // thin along the view
  const CameraSensor camera = Load(Box("Plate", size, centre), "none");
  const Frame frame = offscreen_->Render(scene_, camera);
  ASSERT_EQ(frame.rgb.width, kWidth);
  ASSERT_EQ(frame.rgb.height, kHeight);
  viewer::WritePng((dir_ / "plate.png").string(), frame.rgb);

  double su = 0, sv = 0;
  int n = 0, left = kWidth, right = -1;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (!IsSky(frame.rgb.At(x, y))) {
        su += x + 0.5;
        sv += y + 0.5;
        ++n;
        left = std::min(left, x);
        right = std::max(right, x);
      }
  ASSERT_GT(n, 100) << "the plate is not in the image (" << dir_ / "plate.png" << ")";
  // The camera frame: z along world +x, x along world +z, y along world -y;
  // the plate's near face is half its thickness nearer.
  const Eigen::Vector3d eye(0, 1, 0);
  const double z = centre.x() - size.x() / 2 - eye.x();
  const double xc = centre.z() - eye.z(), yc = -(centre.y() - eye.y());
  const double f = (kWidth / 2.0) / std::tan(kFovDeg * M_PI / 360);
  EXPECT_NEAR(su / n, kWidth / 2.0 + f * xc / z, 1.0);
  EXPECT_NEAR(sv / n, kHeight / 2.0 + f * yc / z, 1.0);
  EXPECT_NEAR(right - left + 1, f * size.z() / z, 1.5);
}

// A wall across the view at 4 m: depth 4 m at the centre and near the
// corners (depth is along the optical axis, not the range along the ray),
// +inf / 0 where nothing is.
TEST_F(CameraRenderTest, DepthOfAPlaneIsItsDistance) {
  const double distance = 4.0;
  const std::string wall = Box("Wall", Eigen::Vector3d(0.2, 3.0, 4.0), Eigen::Vector3d(distance + 0.1, 1, 0));
  for (const std::string format : {"metres", "millimetres"}) {
    const CameraSensor camera = Load(wall, format);
    const Frame frame = offscreen_->Render(scene_, camera);
    const std::vector<uint8_t> bytes = DepthBytes(frame.depth_buffer, camera);
    auto metres = [&](int x, int y) -> double {
      const size_t k = static_cast<size_t>(y) * kWidth + x;
      if (camera.depth == DepthFormat::kMillimetres) {
        uint16_t mm = 0;
        std::memcpy(&mm, bytes.data() + 2 * k, 2);
        return mm / 1000.0;
      }
      float m = 0;
      std::memcpy(&m, bytes.data() + 4 * k, 4);
      return m;
    };
    // The wall spans |z| <= 2, |y - 1| <= 1.5 at 4 m: +-106 x +-160 pixels of f = 277.
    for (const auto& [x, y] : {std::pair{kWidth / 2, kHeight / 2}, std::pair{100, 40},
                              std::pair{210, 200}}) {
      EXPECT_NEAR(metres(x, y), distance, 0.01) << format << " at (" << x << ", " << y << ")";
    }
    // Beyond the wall's side (|x - 160| > 106): sky.
    if (camera.depth == DepthFormat::kMetres)
      EXPECT_TRUE(std::isinf(metres(5, kHeight / 2))) << metres(5, kHeight / 2);
    else
      EXPECT_EQ(metres(5, kHeight / 2), 0.0);
  }
}

}  // namespace
}  // namespace simpartner::camera
