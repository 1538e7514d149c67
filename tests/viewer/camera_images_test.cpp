// The viewer's camera inset on memq: it keeps the newest colour image of
// the camera shown (by name, of the simulation shown), ignores depth and
// other cameras, refuses images that are not what the model's camera sends
// and reports bytes that do not decode, shows an image only once a state
// of its step came, and `i` steps through the model's cameras, then none.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <string>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/viewer/camera_images.h"

namespace simpartner::viewer {
namespace {

image_t Image(const std::string& name, int64_t step, int8_t format = image_t::FORMAT_RGB8,
              int extra_bytes = 0) {
  image_t image{};
  image.simulation_id = 5;
  image.step = step;
  image.name = name;
  image.robot = "R";
  image.width = 4;
  image.height = 2;
  image.format = format;
  image.data.assign(4 * 2 * (format == image_t::FORMAT_RGB8 ? 3 : 4) + extra_bytes, 7);
  image.num_bytes = static_cast<int32_t>(image.data.size());
  return image;
}

// Simulation 5: cameras "Front" and "Rear" of 4 x 2 pixels, colour only.
model_t TwoCameras() {
  model_t m{};
  m.simulation_id = 5;
  for (const char* name : {"Front", "Rear"}) {
    sensor_t s{};
    s.id = static_cast<int32_t>(m.sensors.size());
    s.name = name;
    s.kind = sensor_t::KIND_CAMERA;
    s.params = {4, 2, 1.0, 0.1, 50, 0};
    s.num_params = 6;
    m.sensors.push_back(s);
  }
  sensor_t scanner{};
  scanner.name = "Scanner";
  scanner.kind = sensor_t::KIND_SCANNER;
  m.sensors.push_back(scanner);
  m.num_sensors = 3;
  return m;
}

class CameraImagesTest : public ::testing::Test {
 protected:
  // Publishes image and judges it as the viewer does, with the newest
  // state at step newest_state.
  void Send(image_t image, int64_t newest_state = 1000) {
    image.camera = image.name == "Rear" ? 1 : 0;
    lcm_.publish(channels::kImage, &image);
    while (lcm_.handleTimeout(0) > 0) {
    }
    images_.Judge(model_, newest_state);
  }
  const model_t model_ = TwoCameras();
  lcm::LCM lcm_{"memq://"};
  std::vector<std::string> reports_;
  CameraImages images_{&lcm_, nullptr, [this](const std::string& m) { reports_.push_back(m); },
                       "Front"};
};

TEST_F(CameraImagesTest, KeepsTheNewestColourImageOfTheCameraShown) {
  EXPECT_EQ(images_.Newest(5), nullptr);
  Send(Image("Front", 10));
  Send(Image("Rear", 11));
  Send(Image("Front", 10, image_t::FORMAT_DEPTH_F32));
  ASSERT_NE(images_.Newest(5), nullptr);
  EXPECT_EQ(images_.Newest(5)->step, 10);
  EXPECT_EQ(images_.Newest(5)->format, image_t::FORMAT_RGB8);
  EXPECT_EQ(images_.Newest(6), nullptr);  // another simulation's
  Send(Image("Front", 20));
  EXPECT_EQ(images_.Newest(5)->step, 20);
  EXPECT_TRUE(reports_.empty());
}

// The audit's forged image showed in the inset with no camera running.
// One stamped ahead of the states waits and is never shown; one of the
// camera's state is shown once that state came.
TEST_F(CameraImagesTest, AnImageIsShownOnlyOnceItsStateCame) {
  Send(Image("Front", 10));
  Send(Image("Front", 1000000000000));
  EXPECT_EQ(images_.Newest(5)->step, 10);
  images_.Judge(model_, 2000);
  EXPECT_EQ(images_.Newest(5)->step, 10);
  Send(Image("Front", 2500), 2000);
  EXPECT_EQ(images_.Newest(5)->step, 10);
  images_.Judge(model_, 2500);
  EXPECT_EQ(images_.Newest(5)->step, 2500);
  EXPECT_TRUE(reports_.empty());
}

TEST_F(CameraImagesTest, AnImageThatIsNotTheCamerasIsRefused) {
  image_t small = Image("Front", 10);
  small.width = 1;
  small.data.resize(6);
  small.num_bytes = 6;
  Send(small);
  EXPECT_EQ(images_.Newest(5), nullptr);
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_NE(reports_[0].find("image 'Front': width 1: camera 'Front' is 4 wide"),
            std::string::npos)
      << reports_[0];
}

TEST_F(CameraImagesTest, RefusesWhatDoesNotFit) {
  Send(Image("Front", 10, image_t::FORMAT_RGB8, 5));  // 29 bytes for 4x2 RGB8
  EXPECT_EQ(images_.Newest(5), nullptr);
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_NE(reports_[0].find("image 'Front': num_bytes 29: 4x2 rgb8 is 24 bytes"), std::string::npos)
      << reports_[0];
  const char garbage[] = "not an image";
  lcm_.publish(channels::kImage, garbage, sizeof garbage);
  while (lcm_.handleTimeout(0) > 0) {
  }
  ASSERT_EQ(reports_.size(), 2u);
  EXPECT_NE(reports_[1].find("SIM_IMAGE"), std::string::npos) << reports_[1];
}

TEST_F(CameraImagesTest, TheKeyStepsThroughTheCamerasThenNone) {
  const model_t m = TwoCameras();
  EXPECT_EQ(images_.shown(), "Front");
  images_.ShowNext(m);
  EXPECT_EQ(images_.shown(), "Rear");
  images_.ShowNext(m);
  EXPECT_EQ(images_.shown(), "");
  images_.ShowNext(m);
  EXPECT_EQ(images_.shown(), "Front");
}

}  // namespace
}  // namespace simpartner::viewer
