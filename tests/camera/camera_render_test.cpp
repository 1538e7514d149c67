// simpartner-camera's rendering against the pinhole, as a real process
// under a private Xvfb (llvmpipe) on udpm (ttl=0). The test is the sim: it
// publishes the SIM_MODEL and one SIM_STATE that the sim library makes in
// process for a world of its own. A rig with two cameras (depth in metres,
// depth in millimetres) looks along the world's +x at a red plate off the
// optical axis and a wall behind it. The plate's pixels must have their
// centroid at the pinhole projection of its centre, computed here from the
// poses and the field of view (not with the renderer's matrices), and the
// wall's depth must be its distance along the axis within 1 cm.
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include "../sim_core/test_worlds.h"
#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/image_t.hpp"
#include "simpartner/viewer/xvfb.h"

namespace simpartner::camera {
namespace {

constexpr int kRenderWidth = 320;
constexpr int kRenderHeight = 240;
constexpr double kFovDeg = 60;
constexpr double kWall = 6.0;  // [m] the wall's near face, x = 6, across the view

// Camera `name` 1 m above the rig's origin, looking along +x (camera z =
// x, camera x = z, camera y = -y).
std::string Camera(const std::string& name, const std::string& depth) {
  std::ostringstream fov;
  fov.precision(17);
  fov << kFovDeg * M_PI / 180;
  return R"(<sensor type="Camera" name=")" + name + R"("><bodyRef>Base</bodyRef>
    <transformation>
      <T00>0</T00><T01>0</T01><T02>1</T02><T03>0</T03>
      <T10>0</T10><T11>-1</T11><T12>0</T12><T13>1</T13>
      <T20>1</T20><T21>0</T21><T22>0</T22><T23>0</T23>
    </transformation>
    <rate>30</rate>
    <parameter name="width">)" + std::to_string(kRenderWidth) + R"(</parameter>
    <parameter name="height">)" + std::to_string(kRenderHeight) + R"(</parameter>
    <parameter name="fov">)" + fov.str() + R"(</parameter>
    <parameter name="near">0.1</parameter><parameter name="far">30</parameter>
    <parameter name="depth">)" + depth + R"(</parameter>
  </sensor>)";
}

std::string Rig() {
  return R"(<robot name="Rig"><body type="Box" name="Base"><mass>10</mass>)" +
         sim::testing::Vec("size", 0.2, 0.2, 0.2) + sim::testing::Transform(0, 0, 0) + "</body>" +
         Camera("Metres", "metres") + Camera("Millimetres", "millimetres") + "</robot>";
}

// A red (moving, never stepped) plate, thin along the view, and a brown
// (static) wall; no ground, so the sky is around them.
const Eigen::Vector3d kPlateCentre(5.0, 1.4, 0.8);
const Eigen::Vector3d kPlateSize(0.01, 0.4, 0.6);

std::string World() {
  return R"(<world name="CameraRender">)" + sim::testing::Vec("gravity", 0, -9.81, 0) +
         R"(<object type="Box" name="Plate"><mass>1</mass>)" +
         sim::testing::Vec("size", kPlateSize.x(), kPlateSize.y(), kPlateSize.z()) +
         sim::testing::Transform(kPlateCentre.x(), kPlateCentre.y(), kPlateCentre.z()) +
         R"(</object><object type="Box" name="Wall" static="true">)" +
         sim::testing::Vec("size", 0.2, 6, 6) + sim::testing::Transform(kWall + 0.1, 1, 0) +
         R"(</object><robot name="Rig" file="rig.xml"/></world>)";
}

double DepthAt(const image_t& image, int x, int y) {
  const size_t k = static_cast<size_t>(y) * image.width + x;
  if (image.format == image_t::FORMAT_DEPTH_U16) {
    uint16_t mm = 0;
    std::memcpy(&mm, image.data.data() + 2 * k, 2);
    return mm / 1000.0;
  }
  float m = 0;
  std::memcpy(&m, image.data.data() + 4 * k, 4);
  return m;
}

TEST(CameraRender, PlateAtThePinholeAndWallAtItsDepth) {
  const auto dir = test_support::FreshTestDir("sp_camera_render_");
  viewer::XvfbServer xvfb(640, 480, (dir / "xvfb.log").string());
  const std::string url = test_support::BusUrl(0);
  test_support::BusListener bus(url);
  std::map<std::string, std::vector<image_t>> images;  // by camera
  bus.Subscribe<image_t>(channels::kImage,
                         [&](const image_t& i) { images[i.name].push_back(i); });
  ChildProcess camera(test_support::OnDisplay(
                          xvfb.display(), test_support::BuiltCommand(
                                              "simpartner-camera",
                                              {"--params", "/dev/null", "--lcm-url", url})),
                      (dir / "camera.log").string());

  // The sim's part, in process.
  auto sim = sim::testing::MakeSim(World(), {{"rig.xml", Rig()}});
  model_t model;
  sim->FillModel(&model);
  state_t state;
  sim->FillState(&state);
  ASSERT_TRUE(bus.Until(
      [&] {
        bus.Publish(channels::kModel, model);
        return test_support::ReadText(dir / "camera.log").find(": 2 cameras") != std::string::npos;
      },
      20))
      << test_support::ReadText(dir / "camera.log");
  bus.Publish(channels::kState, state);
  ASSERT_TRUE(bus.Until([&] { return images["Metres"].size() == 2 && images["Millimetres"].size() == 2; }, 10))
      << test_support::ReadText(dir / "camera.log");
  camera.Signal(SIGTERM);
  EXPECT_EQ(camera.Wait(std::chrono::seconds(10)), 0);

  // The plate: the centroid of the red pixels. Camera frame: z along world
  // +x, x along world +z, y along world -y, from (0, 1, 0); the plate's near
  // face is half its thickness nearer.
  const image_t& rgb = images["Metres"][0];
  ASSERT_EQ(rgb.format, image_t::FORMAT_RGB8);
  ASSERT_EQ(rgb.step, 0);
  double su = 0, sv = 0;
  int n = 0, left = kRenderWidth, right = -1;
  for (int y = 0; y < kRenderHeight; ++y)
    for (int x = 0; x < kRenderWidth; ++x) {
      const uint8_t* p = &rgb.data[(static_cast<size_t>(y) * kRenderWidth + x) * 3];
      if (p[0] - std::max(p[1], p[2]) > 60) {
        su += x + 0.5;
        sv += y + 0.5;
        ++n;
        left = std::min(left, x);
        right = std::max(right, x);
      }
    }
  ASSERT_GT(n, 100) << "the plate is not in the image";
  const double z = kPlateCentre.x() - kPlateSize.x() / 2;
  const double xc = kPlateCentre.z(), yc = -(kPlateCentre.y() - 1.0);
  const double f = (kRenderWidth / 2.0) / std::tan(kFovDeg * M_PI / 360);
  EXPECT_NEAR(su / n, kRenderWidth / 2.0 + f * xc / z, 1.0);
  EXPECT_NEAR(sv / n, kRenderHeight / 2.0 + f * yc / z, 1.0);
  EXPECT_NEAR(right - left + 1, f * kPlateSize.z() / z, 1.5);

  // The wall: 6 m along the axis at the centre and near the corners (depth
  // is along z, not the range along the ray); +inf / 0 beside it (|z| > 3
  // at u < 22).
  for (const char* name : {"Metres", "Millimetres"}) {
    SCOPED_TRACE(name);
    const image_t& depth = images[name][1];
    ASSERT_EQ(depth.format, std::string(name) == "Metres" ? image_t::FORMAT_DEPTH_F32
                                                          : image_t::FORMAT_DEPTH_U16);
    ASSERT_EQ(depth.step, 0);
    for (const auto& [x, y] : {std::pair{kRenderWidth / 2, kRenderHeight / 2}, std::pair{30, 10},
                              std::pair{290, 230}})
      EXPECT_NEAR(DepthAt(depth, x, y), kWall, 0.01) << "at (" << x << ", " << y << ")";
    const double beside = DepthAt(depth, 5, kRenderHeight / 2);
    if (depth.format == image_t::FORMAT_DEPTH_F32)
      EXPECT_TRUE(std::isinf(beside)) << beside;
    else
      EXPECT_EQ(beside, 0.0);
  }
  if (!HasFailure()) std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace simpartner::camera
