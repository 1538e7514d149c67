// simpartner-viewer as a real process: its own Xvfb per test, a real
// simpartner-sim, real LCM multicast (udpm, ttl=0, a port per test). The
// screenshots are checked pixel by pixel: each body appears where the pose
// in SIM_STATE says, projected with the viewer's camera maths, and the sky
// shows where nothing is.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include "../support/bus_listener.h"
#include "../support/bus_url.h"
#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/sim_process.h"
#include "../support/test_dir.h"
#include "../support/text_file.h"
#include "../support/wait.h"
#include "simpartner/channels.h"
#include "simpartner/child_process.h"
#include "simpartner/control_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/soil_ruts_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/viewer/camera.h"
#include "simpartner/viewer/options.h"
#include "simpartner/png_image.h"
#include "simpartner/viewer/xvfb.h"

namespace simpartner::viewer {
namespace {

constexpr int kWidth = 800;
constexpr int kHeight = 450;
// Looks along -x at (0, 1.2, 0) from 6 m, 8 degrees from above.
constexpr const char* kCamera = "0,1.2,0,0,8,6";
// How the viewer's log line for a screenshot begins; the file follows.
constexpr const char* kScreenshotLine = "simpartner-viewer: screenshot ";

std::string Transform(double x, double y, double z, double yaw_deg = 0) {
  const double c = std::cos(yaw_deg * M_PI / 180), s = std::sin(yaw_deg * M_PI / 180);
  std::ostringstream t;
  t << "<transformation><T00>" << c << "</T00><T01>0</T01><T02>" << s << "</T02><T03>" << x
    << "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" << y
    << "</T13><T20>" << -s << "</T20><T21>0</T21><T22>" << c << "</T22><T23>" << z
    << "</T23></transformation>";
  return t.str();
}

// No ground, so the sky is behind every body: a fixed box, cylinder and
// capsule, and a pendulum (a sphere hinged to the world 1 m from its
// anchor, released level) that swings in the image plane.
std::string ShapesWorld() {
  return R"(<world name="ViewerShapes">
  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>
  <object type="Box" name="Crate" static="true"><size><x>0.8</x><y>0.8</y><z>0.8</z></size>)" +
         Transform(0, 0.6, 1.3, 30) + R"(</object>
  <object type="Cylinder" name="Drum" static="true"><radius>0.3</radius><length>0.8</length>)" +
         Transform(0.3, 0.5, -1.3) + R"(</object>
  <object type="Capsule" name="Pill" static="true"><radius>0.15</radius><length>0.5</length>)" +
         Transform(-0.5, 0.2, 0) + R"(</object>
  <object type="Sphere" name="Bob"><mass>1</mass><radius>0.2</radius>)" +
         Transform(0, 2.4, -1.0) + R"(</object>
  <joint type="Hinge" name="Swing"><body1>Bob</body1><body2>world</body2>
    <anchor><x>0</x><y>2.4</y><z>0</z></anchor><axis1><x>1</x><y>0</y><z>0</z></axis1></joint>
</world>)";
}

// A plane, a bumpy heightfield and a fixed sphere high up where
// ViewerShapes has only sky.
std::string TerrainWorld() {
  std::string samples;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 7; ++c) samples += std::to_string((r * 3 + c * 5) % 4) + " ";
  return R"(<world name="ViewerTerrain">
  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>
  <surface><a>0</a><b>1</b><c>0</c><d>-0.5</d></surface>
  <heightfield rows="5" columns="7"><width>6</width><depth>4</depth><scale>0.1</scale>
    <position><x>0</x><y>0</y><z>0</z></position><samples>)" +
         samples + R"(</samples></heightfield>
  <object type="Sphere" name="Beacon" static="true"><radius>0.3</radius>)" +
         Transform(0, 3.0, 1.6) + R"(</object>
</world>)";
}

// A field 6 m along x, 4 m along z, flat but for a ridge 0.8 m high
// along z at x = 0: from the test's camera (along -x, from above x = 6 m)
// it hides the ground from x = -3 to about -0.3 m.
std::string RidgeWorld() {
  return R"(<world name="ViewerRidge">
  <gravity><x>0</x><y>-9.81</y><z>0</z></gravity>
  <heightfield rows="3" columns="5"><width>6</width><depth>4</depth>
    <position><x>0</x><y>0</y><z>0</z></position>
    <samples>0 0 0.8 0 0  0 0 0.8 0 0  0 0 0.8 0 0</samples></heightfield>
</world>)";
}

struct Pose {
  Eigen::Vector3d position;
};

// Test side of the bus: the model and every body position by step.
class Listener : public test_support::BusListener {
 public:
  explicit Listener(const std::string& url) : BusListener(url) {
    Subscribe<state_t>(channels::kState, [this](const state_t& s) { OnState(s); });
    Subscribe<model_t>(channels::kModel, [this](const model_t& m) {
      model = m;
      has_model = true;
    });
    Subscribe<status_t>(channels::kStatus, [this](const status_t& s) {
      run_state = s.run_state;
      status_step = s.step;
    });
  }
  int BodyIndex(const std::string& name) const {
    for (const body_t& b : model.bodies)
      if (b.name == name) return b.id;
    ADD_FAILURE() << "no body " << name;
    return 0;
  }

  model_t model;
  bool has_model = false;
  int8_t run_state = -1;     // of the last SIM_STATUS
  int64_t status_step = -1;  // of the last SIM_STATUS
  int64_t last_step = -1;    // of the last SIM_STATE
  std::map<int64_t, std::vector<Eigen::Vector3d>> positions;  // step -> body positions
  int64_t last_simulation = 0;

 private:
  void OnState(const state_t& s) {
    std::vector<Eigen::Vector3d>& p = positions[s.step];
    p.clear();
    for (const body_state_t& b : s.bodies) p.emplace_back(b.position[0], b.position[1], b.position[2]);
    last_simulation = s.simulation_id;
    last_step = s.step;
  }
};

using test_support::BusUrl;
using test_support::OnDisplay;
using test_support::ReadText;
using test_support::SimProcess;

double ColorDistance(const RgbImage::Rgb& a, const RgbImage::Rgb& b) {
  return std::sqrt(static_cast<double>((a.r - b.r) * (a.r - b.r) + (a.g - b.g) * (a.g - b.g) +
                                       (a.b - b.b) * (a.b - b.b)));
}

class ViewerProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test_support::FreshTestDir("sp_viewer_process_");
    std::ofstream(dir_ / "shapes.xml") << ShapesWorld();
    std::ofstream(dir_ / "terrain.xml") << TerrainWorld();
    std::ofstream(dir_ / "ridge.xml") << RidgeWorld();
    xvfb_ = std::make_unique<XvfbServer>(1280, 720, (dir_ / "xvfb.log").string());
  }
  void TearDown() override {
    xvfb_.reset();
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }

  std::unique_ptr<SimProcess> StartSim(const std::string& world, const std::string& url,
                                       const std::string& log, std::vector<std::string> extra = {}) {
    extra.insert(extra.begin(), "--duration=60");
    return std::make_unique<SimProcess>((dir_ / world).string(), url, (dir_ / log).string(), extra);
  }

  std::unique_ptr<ChildProcess> StartViewer(const std::string& url, const std::string& log,
                                            std::vector<std::string> extra) {
    std::vector<std::string> args = {"--params", "/dev/null", "--lcm-url", url,
                                     "--width", std::to_string(kWidth), "--height", std::to_string(kHeight),
                                     "--camera", kCamera};
    args.insert(args.end(), extra.begin(), extra.end());
    // In the test's directory: a screenshot taken with the key (p) goes there.
    return std::make_unique<ChildProcess>(
        OnDisplay(xvfb_->display(),
                  test_support::InDirectory(dir_.string(),
                                            test_support::BuiltCommand("simpartner-viewer", args))),
        (dir_ / log).string());
  }

  std::string Read(const std::string& log) const { return ReadText(dir_ / log); }
  // Until the log holds `text`, receiving on `bus` meanwhile when there is one.
  bool WaitForText(const std::string& log, const std::string& text, double seconds,
                   Listener* bus = nullptr) {
    return bus != nullptr ? bus->UntilFileHolds(dir_ / log, text, seconds)
                          : test_support::WaitForText(dir_ / log, text, seconds);
  }
  // Real key presses (XTEST): `args` for xdotool on the test's display.
  void Xdotool(const std::vector<std::string>& args) const {
    const test_support::ProgramRun run =
        test_support::RunXdotool(xvfb_->display(), args, (dir_ / "xdotool.log").string());
    EXPECT_EQ(run.status, 0) << run.output;
  }
  // The file the viewer's last screenshot went to (its log says).
  std::string ScreenshotFile(const std::string& log) const {
    const std::string text = Read(log);
    const size_t line = text.rfind(kScreenshotLine);
    if (line == std::string::npos) return {};
    const size_t from = line + std::strlen(kScreenshotLine);
    return (dir_ / text.substr(from, text.find(" (", from) - from)).string();
  }
  // Step of the state the screenshot shows, from the viewer's log line.
  int64_t ScreenshotStep(const std::string& log) const {
    const std::string text = Read(log);
    const size_t line = text.find(kScreenshotLine);
    const size_t step = text.find(", step ", line == std::string::npos ? text.size() : line);
    if (step == std::string::npos) return -1;
    return std::atoll(text.c_str() + step + 7);
  }

  Eigen::Vector2d Pixel(const Eigen::Vector3d& p, const Eigen::Vector3d& up) const {
    const Camera camera = CameraFromSpec(Spec(), up);
    const auto pixel = camera.Project(p, kWidth, kHeight);
    EXPECT_TRUE(pixel && pixel->x() >= 0 && pixel->x() < kWidth && pixel->y() >= 0 &&
                pixel->y() < kHeight)
        << p.transpose() << " is not in the picture";
    return pixel.value_or(Eigen::Vector2d(-1, -1));
  }
  static CameraSpec Spec() {
    CameraSpec spec;
    spec.target[1] = 1.2;
    spec.yaw_deg = 0;
    spec.pitch_deg = 8;
    spec.distance = 6;
    return spec;
  }
  RgbImage::Rgb At(const RgbImage& image, const Eigen::Vector2d& pixel) const {
    return image.At(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
  }

  // Expects the screenshot to show each named body at its position in the
  // state of step `step`, and the sky at points away from every body.
  void ExpectBodiesWhereTheStateSays(const RgbImage& image, const Listener& bus, int64_t step,
                                     const std::vector<std::string>& names) {
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    ASSERT_TRUE(bus.positions.count(step)) << "no state of step " << step << " on the bus";
    const std::vector<Eigen::Vector3d>& at = bus.positions.at(step);
    const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
    // The sky: well above everything.
    const RgbImage::Rgb sky = At(image, Pixel(Eigen::Vector3d(0, 3.4, 2.2), up));
    for (const Eigen::Vector3d& empty :
         {Eigen::Vector3d(0, 3.4, -2.2), Eigen::Vector3d(0, 1.5, -2.5), Eigen::Vector3d(0, 0.6, 2.6)}) {
      EXPECT_LT(ColorDistance(At(image, Pixel(empty, up)), sky), 12)
          << "something drawn at " << empty.transpose() << " where no body is";
    }
    for (const std::string& name : names) {
      const Eigen::Vector3d p = at.at(static_cast<size_t>(bus.BodyIndex(name)));
      const Eigen::Vector2d pixel = Pixel(p, up);
      EXPECT_GT(ColorDistance(At(image, pixel), sky), 60)
          << name << " at " << p.transpose() << " (pixel " << pixel.transpose()
          << ") is not drawn there";
    }
  }

  std::filesystem::path dir_;
  std::unique_ptr<XvfbServer> xvfb_;
};

void Quit(test_support::BusListener& bus) {
  control_t c{};
  c.action = control_t::ACTION_QUIT;
  c.sender = "viewer-test";
  bus.Publish(channels::kControl, c);
}

// Fraction of pixels that differ from the sky in the middle 60 % of the
// rectangle around the projected corners of a cube of edge `edge` at
// `centre` (a cube well inside the body looked at).
double CoveredFraction(const RgbImage& image, const Eigen::Vector3d& centre, double edge,
                       const std::function<Eigen::Vector2d(const Eigen::Vector3d&)>& pixel,
                       const RgbImage::Rgb& sky) {
  Eigen::AlignedBox2d box;
  for (int k = 0; k < 8; ++k)
    box.extend(pixel(centre + edge / 2 *
                                  Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1)));
  const Eigen::Vector2d c = box.center(), half = 0.3 * box.sizes();
  int covered = 0, total = 0;
  for (int y = static_cast<int>(c.y() - half.y()); y <= c.y() + half.y(); ++y)
    for (int x = static_cast<int>(c.x() - half.x()); x <= c.x() + half.x(); ++x) {
      ++total;
      covered += ColorDistance(image.At(x, y), sky) > 30;
    }
  return total == 0 ? 0 : static_cast<double>(covered) / total;
}

TEST_F(ViewerProcessTest, ScreenshotShowsEveryBodyWhereItsStateSaysAndWireframeDiffers) {
  const std::string url = BusUrl(1);
  Listener bus(url);
  auto sim = StartSim("shapes.xml", url, "sim.log");
  ASSERT_TRUE(bus.Until([&] { return bus.has_model && !bus.positions.empty(); }, 15)) << Read("sim.log");

  // The pendulum must have swung from where it started, or the check below
  // could not tell the state's pose from the model's initial one. Released
  // level, it is back there once a period (about 2.4 s), within 5 cm for
  // about 0.2 s of it: a screenshot that falls there is taken again.
  const std::string solid = (dir_ / "solid.png").string();
  const Eigen::Vector3d bob_start(0, 2.4, -1.0);
  int64_t step = -1;
  double swung = 0;
  for (int attempt = 0; attempt < 3 && swung <= 0.05; ++attempt) {
    const std::string log = "viewer" + std::to_string(attempt) + ".log";
    auto viewer = StartViewer(url, log, {"--hide", "hud,grid", "--screenshot", solid, "--after", "2.5"});
    ASSERT_TRUE(WaitForText(log, "simpartner-viewer: screenshot", 30, &bus)) << Read(log);
    bus.Pump(0.3);
    ASSERT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read(log);
    step = ScreenshotStep(log);
    ASSERT_GT(step, 0) << Read(log);
    swung = (bus.positions.at(step)[static_cast<size_t>(bus.BodyIndex("Bob"))] - bob_start).norm();
    if (swung <= 0.05)
      std::cout << "screenshot at step " << step << ": the pendulum " << swung
                << " m from its release pose; taken again\n";
  }
  ASSERT_GT(swung, 0.05) << "three screenshots with the pendulum at its release pose";
  const RgbImage image = ReadPng(solid);
  ExpectBodiesWhereTheStateSays(image, bus, step, {"Crate", "Drum", "Pill", "Bob"});

  // Not blank: a good share of the image is bodies.
  const RgbImage::Rgb sky = image.At(2, kHeight / 2);
  int drawn = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) drawn += ColorDistance(image.At(x, y), sky) > 30;
  EXPECT_GT(drawn, kWidth * kHeight / 50);

  // Wireframe: the crate's faces are no longer filled.
  const std::string wire = (dir_ / "wire.png").string();
  auto wire_viewer = StartViewer(url, "wire.log", {"--hide", "hud,grid", "--show", "wireframe",
                                                   "--screenshot", wire, "--after", "2"});
  ASSERT_EQ(wire_viewer->Wait(std::chrono::seconds(30)).value_or(-1), 0) << Read("wire.log");
  const RgbImage wire_image = ReadPng(wire);
  auto pixel = [&](const Eigen::Vector3d& p) { return Pixel(p, Eigen::Vector3d::UnitY()); };
  const Eigen::Vector3d crate = bus.positions.at(step)[static_cast<size_t>(bus.BodyIndex("Crate"))];
  const double solid_cover = CoveredFraction(image, crate, 0.5, pixel, sky);
  const double wire_cover = CoveredFraction(wire_image, crate, 0.5, pixel, sky);
  EXPECT_GT(solid_cover, 0.95);
  EXPECT_LT(wire_cover, 0.5);
  int differing = 0;
  for (size_t i = 0; i < image.pixels.size(); i += 3)
    differing += std::abs(image.pixels[i] - wire_image.pixels[i]) > 30;
  EXPECT_GT(differing, 1000);
  Quit(bus);
  EXPECT_EQ(sim->Wait(std::chrono::seconds(10)).value_or(-1), 0);
}

TEST_F(ViewerProcessTest, LateViewerAsksForTheModelAndDrawsAllOfIt) {
  const std::string url = BusUrl(2);
  Listener bus(url);
  // No periodic announcement: only a request brings the model.
  auto sim = StartSim("shapes.xml", url, "sim.log", {"--modelPeriod=3600"});
  ASSERT_TRUE(bus.Until([&] { return bus.has_model; }, 15)) << Read("sim.log");
  bus.Pump(3.0);  // the viewer comes 3 s later
  const std::string shot = (dir_ / "late.png").string();
  auto viewer = StartViewer(url, "viewer.log", {"--hide", "hud,grid", "--screenshot", shot,
                                                "--after", "2"});
  ASSERT_TRUE(WaitForText("viewer.log", "simpartner-viewer: screenshot", 30, &bus)) << Read("viewer.log");
  bus.Pump(0.3);
  ASSERT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("viewer.log");
  const std::string log = Read("viewer.log");
  EXPECT_NE(log.find("model of simulation " + std::to_string(bus.model.simulation_id) +
                     ": world 'ViewerShapes', 4 bodies"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("4 bodies drawn"), std::string::npos) << log;
  ExpectBodiesWhereTheStateSays(ReadPng(shot), bus, ScreenshotStep("viewer.log"),
                                {"Crate", "Drum", "Pill", "Bob"});
  Quit(bus);
  EXPECT_EQ(sim->Wait(std::chrono::seconds(10)).value_or(-1), 0);
}

TEST_F(ViewerProcessTest, SimRestartedWithAnotherWorldShowsTheNewModel) {
  const std::string url = BusUrl(3);
  Listener bus(url);
  const std::string restarted = (dir_ / "restarted.png").string();
  auto viewer = StartViewer(url, "viewer.log", {"--hide", "hud,grid", "--screenshot", restarted,
                                                "--after", "9"});
  auto first = StartSim("shapes.xml", url, "first.log");
  ASSERT_TRUE(WaitForText("viewer.log", "world 'ViewerShapes'", 20, &bus)) << Read("viewer.log");
  Quit(bus);
  ASSERT_EQ(first->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("first.log");
  auto second = StartSim("terrain.xml", url, "second.log");
  ASSERT_TRUE(WaitForText("viewer.log", "simpartner-viewer: screenshot", 30, &bus)) << Read("viewer.log");
  ASSERT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("viewer.log");
  EXPECT_NE(Read("viewer.log").find("world 'ViewerTerrain', 1 bodies"), std::string::npos)
      << Read("viewer.log");

  // A viewer started fresh on the second sim sees the same picture.
  const std::string fresh = (dir_ / "fresh.png").string();
  auto fresh_viewer = StartViewer(url, "fresh.log", {"--hide", "hud,grid", "--screenshot", fresh,
                                                     "--after", "2"});
  ASSERT_EQ(fresh_viewer->Wait(std::chrono::seconds(30)).value_or(-1), 0) << Read("fresh.log");
  const RgbImage a = ReadPng(restarted), b = ReadPng(fresh);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.pixels.size(); i += 3)
    differing += ColorDistance({a.pixels[i], a.pixels[i + 1], a.pixels[i + 2]},
                               {b.pixels[i], b.pixels[i + 1], b.pixels[i + 2]}) > 12;
  EXPECT_LT(differing, a.pixels.size() / 3 / 200) << "the restarted viewer shows something else";

  // And that picture is the terrain world: the beacon where the first world
  // had sky, the heightfield and the plane below, no crate.
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const RgbImage::Rgb sky = At(a, Pixel(Eigen::Vector3d(0, 3.4, -2.2), up));
  EXPECT_GT(ColorDistance(At(a, Pixel(Eigen::Vector3d(0, 3.0, 1.6), up)), sky), 60) << "beacon";
  const RgbImage::Rgb plane = At(a, Pixel(Eigen::Vector3d(-40, -0.5, 8), up));
  EXPECT_GT(ColorDistance(plane, sky), 30) << "plane";
  const RgbImage::Rgb field = At(a, Pixel(Eigen::Vector3d(1.5, 0.15, -1.0), up));
  EXPECT_GT(ColorDistance(field, sky), 30) << "heightfield";
  EXPECT_GT(ColorDistance(field, plane), 30) << "heightfield";
  const RgbImage::Rgb where_bob_was = At(a, Pixel(Eigen::Vector3d(0, 2.4, -1.0), up));
  EXPECT_LT(ColorDistance(where_bob_was, sky), 12) << "the first world's pendulum is still drawn";
  Quit(bus);
  EXPECT_EQ(second->Wait(std::chrono::seconds(10)).value_or(-1), 0);
}

TEST_F(ViewerProcessTest, BadStatesAreCountedAndIgnoredWithoutACrash) {
  const std::string url = BusUrl(4);
  Listener bus(url);
  // At 50 states a second: at 1,000 the sanitized viewer beside a busy
  // loop on each core handled 363 states in 2.7 s, LCM's queue for it
  // (2,000) filled and the bad states, the newest, were dropped uncounted.
  auto sim = StartSim("shapes.xml", url, "sim.log", {"--speed=0.05"});
  ASSERT_TRUE(bus.Until([&] { return bus.has_model && !bus.positions.empty(); }, 15)) << Read("sim.log");
  // The screenshot is taken with the key (p) once the bad states are sent,
  // and the viewer ends on SIGTERM after it: a screenshot timed from the
  // start raced them under load (the viewer learned the model late and
  // ended before the last of them).
  auto viewer = StartViewer(url, "viewer.log", {"--hide", "hud,grid", "--quit-after", "120"});
  ASSERT_TRUE(WaitForText("viewer.log", "model of simulation", 20, &bus)) << Read("viewer.log");

  const model_t& m = bus.model;
  auto good = [&] {
    state_t s{};
    s.simulation_id = m.simulation_id;
    s.step = 1;
    s.bodies.resize(static_cast<size_t>(m.num_bodies));
    for (body_state_t& b : s.bodies) b.orientation[0] = 1;
    s.num_bodies = m.num_bodies;
    s.joints.resize(static_cast<size_t>(m.num_joints));
    s.num_joints = m.num_joints;
    return s;
  };
  for (int i = 0; i < 3; ++i) {
    state_t more = good();
    more.bodies.resize(more.bodies.size() + 2);
    more.num_bodies += 2;
    bus.Publish(channels::kState, more);
    state_t other = good();
    other.simulation_id = m.simulation_id + 1000 + i;
    bus.Publish(channels::kState, other);
    state_t nan = good();
    nan.bodies[1].position[0] = std::nan("");
    bus.Publish(channels::kState, nan);
    state_t zero_quaternion = good();
    zero_quaternion.bodies[0].orientation[0] = 0;
    bus.Publish(channels::kState, zero_quaternion);
    const uint8_t garbage[] = {0xde, 0xad, 0xbe, 0xef, 1, 2, 3};
    bus.PublishBytes(channels::kState, garbage, sizeof garbage);
    bus.Pump(0.02);
  }
  // No window manager: the keyboard's focus follows the pointer onto the
  // viewer's window, which is centred on the screen.
  Xdotool({"mousemove", "640", "360"});
  Xdotool({"key", "p"});
  ASSERT_TRUE(WaitForText("viewer.log", "simpartner-viewer: screenshot", 30, &bus)) << Read("viewer.log");
  const std::string shot = ScreenshotFile("viewer.log");
  // It counts, before it ends, what came before the signal.
  viewer->Signal(SIGTERM);
  ASSERT_EQ(viewer->Wait(std::chrono::seconds(30)).value_or(-1), 0) << Read("viewer.log");
  const std::string log = Read("viewer.log");
  // Each kind described once, with channel, field and value...
  EXPECT_NE(log.find("SIM_STATE: num_bodies = " + std::to_string(m.num_bodies + 2)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("SIM_STATE: simulation_id = " + std::to_string(m.simulation_id + 1000)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("SIM_STATE: bodies[1].position[0] = nan (body '" + m.bodies[1].name + "'"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("SIM_STATE: bodies[0].orientation has length 0"), std::string::npos) << log;
  EXPECT_NE(log.find("SIM_STATE: 7 bytes refused as simpartner.state_t: only 7 bytes: too short "
                     "for a fingerprint; ignored"),
            std::string::npos)
      << log;
  // ...and every one counted.
  EXPECT_NE(log.find("ignored: 3 undecodable, 3 other simulation, 3 body count, 3 non-finite, "
                     "3 bad quaternion"),
            std::string::npos)
      << log;
  // The bodies are still drawn from the sim's good states.
  ExpectBodiesWhereTheStateSays(ReadPng(shot), bus, ScreenshotStep("viewer.log"),
                                {"Crate", "Drum", "Pill", "Bob"});
  Quit(bus);
  EXPECT_EQ(sim->Wait(std::chrono::seconds(10)).value_or(-1), 0);
}

// A 0.3 x 0.4 m rut 5 cm deep in the field at (x, 0), 2 cm cells.
soil_ruts_t RidgeRut(int64_t simulation_id, double x) {
  soil_ruts_t m{};
  m.simulation_id = simulation_id;
  m.snapshot = true;
  m.parts = 1;
  m.up[1] = 1;
  m.u_axis[0] = 1;
  m.cell_size = 0.02;
  m.ground = soil_ruts_t::GROUND_HEIGHTFIELD;
  const auto u0 = static_cast<int32_t>(std::lround(x / 0.02));
  for (int32_t u = u0 - 7; u < u0 + 8; ++u)
    for (int32_t w = -10; w < 10; ++w) {
      m.u.push_back(u);
      m.w.push_back(w);
      m.depth.push_back(0.05f);
    }
  m.num_cells = static_cast<int32_t>(m.depth.size());
  return m;
}

// Ruts lie in the ground: what stands before them hides them (here a
// ridge of the field), and the ground around them does not.
TEST_F(ViewerProcessTest, ARidgeHidesTheRutBehindItAndNotTheOneBefore) {
  const std::string url = BusUrl(8);
  Listener bus(url);
  auto sim = StartSim("ridge.xml", url, "sim.log");
  ASSERT_TRUE(bus.Until([&] { return bus.has_model; }, 15)) << Read("sim.log");
  const std::string shot = (dir_ / "ridge.png").string();
  auto viewer = StartViewer(url, "viewer.log", {"--hide", "hud,grid", "--screenshot", shot,
                                                "--after", "3"});
  ASSERT_TRUE(WaitForText("viewer.log", "model of simulation", 20, &bus)) << Read("viewer.log");
  // Both ruts in one message: the field's snapshot.
  soil_ruts_t ruts = RidgeRut(bus.model.simulation_id, 2.25);
  const soil_ruts_t behind = RidgeRut(bus.model.simulation_id, -2.25);
  ruts.u.insert(ruts.u.end(), behind.u.begin(), behind.u.end());
  ruts.w.insert(ruts.w.end(), behind.w.begin(), behind.w.end());
  ruts.depth.insert(ruts.depth.end(), behind.depth.begin(), behind.depth.end());
  ruts.num_cells = static_cast<int32_t>(ruts.depth.size());
  bus.Publish(channels::kSoilRuts, ruts);
  ASSERT_TRUE(WaitForText("viewer.log", "simpartner-viewer: screenshot", 30, &bus)) << Read("viewer.log");
  ASSERT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("viewer.log");
  const RgbImage image = ReadPng(shot);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  // Each rut's floor against the ground beside it (1.2 m along z, at the
  // same x: the same slope of the field before the camera).
  auto contrast = [&](double x) {
    return ColorDistance(At(image, Pixel(Eigen::Vector3d(x, -0.05, 0), up)),
                         At(image, Pixel(Eigen::Vector3d(x, 0, 1.2), up)));
  };
  EXPECT_GT(contrast(2.25), 40) << "the rut before the ridge is not drawn";
  EXPECT_LT(contrast(-2.25), 12) << "the rut behind the ridge shows through it";
  Quit(bus);
  EXPECT_EQ(sim->Wait(std::chrono::seconds(10)).value_or(-1), 0);
}

// SIGTERM (or SIGINT) closes the window and ends the viewer cleanly, even
// while it waits on the bus, with its frame figures.
TEST_F(ViewerProcessTest, SigtermEndsTheViewerCleanly) {
  const std::string url = BusUrl(6);
  auto viewer = StartViewer(url, "viewer.log", {});
  ASSERT_TRUE(WaitForText("viewer.log", "listening on", 20)) << Read("viewer.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  viewer->Signal(SIGTERM);
  EXPECT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("viewer.log");
  EXPECT_NE(Read("viewer.log").find("frames in"), std::string::npos) << Read("viewer.log");
}

// Real key presses (XTEST, through xdotool) reach the viewer's window and
// become SIM_CONTROL messages the sim obeys: space pauses and resumes, n
// steps once, r resets to step 0, Esc closes the viewer.
TEST_F(ViewerProcessTest, KeysPauseStepResetAndResumeTheSim) {
  const std::string url = BusUrl(5);
  Listener bus(url);
  auto sim = StartSim("shapes.xml", url, "sim.log");
  ASSERT_TRUE(bus.Until([&] { return bus.has_model && bus.last_step > 0; }, 15)) << Read("sim.log");
  auto viewer = StartViewer(url, "viewer.log", {"--quit-after", "60"});
  ASSERT_TRUE(WaitForText("viewer.log", "model of simulation", 20, &bus)) << Read("viewer.log");
  // No window manager: keyboard focus follows the pointer onto the
  // viewer's window, which is centred on the screen.
  Xdotool({"mousemove", "640", "360"});

  Xdotool({"key", "space"});
  ASSERT_TRUE(bus.Until([&] { return bus.run_state == status_t::RUN_PAUSED; }, 10))
      << Read("viewer.log") << Read("sim.log");
  bus.Pump(0.3);
  const int64_t paused_at = bus.last_step;
  Xdotool({"key", "n"});
  ASSERT_TRUE(bus.Until([&] { return bus.last_step == paused_at + 1; }, 10))
      << "step after n: " << bus.last_step << ", paused at " << paused_at;
  bus.Pump(0.5);
  EXPECT_EQ(bus.last_step, paused_at + 1);  // one step only, still paused

  // A reset starts a new simulation (new id, step 0, still paused); the
  // viewer takes up its model.
  const int64_t before_reset = bus.model.simulation_id;
  Xdotool({"key", "r"});
  ASSERT_TRUE(bus.Until([&] { return bus.status_step == 0 && bus.model.simulation_id != before_reset; },
                        10))
      << "status step " << bus.status_step;
  EXPECT_TRUE(WaitForText("viewer.log",
                          "model of simulation " + std::to_string(bus.model.simulation_id), 10,
                          &bus))
      << Read("viewer.log");
  Xdotool({"key", "space"});
  ASSERT_TRUE(bus.Until([&] { return bus.run_state == status_t::RUN_RUNNING && bus.last_step > 100; },
                        10))
      << "step " << bus.last_step;

  Xdotool({"key", "Escape"});
  EXPECT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("viewer.log");
  Quit(bus);
  EXPECT_EQ(sim->Wait(std::chrono::seconds(10)).value_or(-1), 0);
}

// The stock LCM tools: lcm-logger records 3 s of a real sim;
// after the sim is gone, lcm-logplayer replays the recording into a fresh
// viewer, which learns the model from it and draws the replayed states
// where they say.
TEST_F(ViewerProcessTest, LcmLogplayerReplayIsDrawnLikeTheLiveRun) {
  const std::string url = BusUrl(7);
  const std::string recording = (dir_ / "run.lcmlog").string();
  int64_t recorded_id = 0;
  {
    auto recorder = std::make_unique<ChildProcess>(
        std::vector<std::string>{"/usr/bin/lcm-logger", "--quiet", "--force", "--lcm-url=" + url,
                                 recording},
        (dir_ / "lcm-logger.log").string());
    Listener live(url);
    auto sim = StartSim("shapes.xml", url, "sim.log", {"--duration=3"});
    ASSERT_TRUE(live.Until([&] { return live.has_model; }, 15)) << Read("sim.log");
    recorded_id = live.model.simulation_id;
    ASSERT_EQ(sim->Wait(std::chrono::seconds(30)).value_or(-1), 0) << Read("sim.log");
    live.Pump(0.5);  // lcm-logger flushes every 100 ms
    recorder->Signal(SIGINT);
    ASSERT_EQ(recorder->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("lcm-logger.log");
  }
  ASSERT_GT(std::filesystem::file_size(recording), 100000u);

  Listener bus(url);
  const std::string shot = (dir_ / "replay.png").string();
  auto viewer = StartViewer(url, "viewer.log", {"--hide", "hud,grid", "--screenshot", shot,
                                                "--after", "2"});
  ASSERT_TRUE(WaitForText("viewer.log", "simpartner-viewer:", 30, &bus)) << Read("viewer.log");
  auto player = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/bin/lcm-logplayer", "--lcm-url=" + url, recording},
      (dir_ / "lcm-logplayer.log").string());
  ASSERT_TRUE(WaitForText("viewer.log", "simpartner-viewer: screenshot", 30, &bus)) << Read("viewer.log");
  bus.Pump(0.3);
  ASSERT_EQ(viewer->Wait(std::chrono::seconds(10)).value_or(-1), 0) << Read("viewer.log");
  ASSERT_EQ(player->Wait(std::chrono::seconds(30)).value_or(-1), 0) << Read("lcm-logplayer.log");
  const std::string log = Read("viewer.log");
  EXPECT_NE(log.find("model of simulation " + std::to_string(recorded_id) +
                     ": world 'ViewerShapes', 4 bodies"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("4 bodies drawn"), std::string::npos) << log;
  const int64_t step = ScreenshotStep("viewer.log");
  ASSERT_GT(step, 0) << log;
  ExpectBodiesWhereTheStateSays(ReadPng(shot), bus, step, {"Crate", "Drum", "Pill", "Bob"});
}

}  // namespace
}  // namespace simpartner::viewer
