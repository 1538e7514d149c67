// The client's camera images on memq: the newest colour and depth image of
// each camera of the model are kept; an image that does not fit its camera
// (index, kind, name, format, resolution, byte count) or forged bytes are
// dropped with a line naming SIM_IMAGE, the field and its value, and never
// replace what is kept; another simulation's are dropped quietly.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <string>
#include <vector>

#include "simpartner/channels.h"
#include "simpartner/client/image_store.h"
#include "simpartner/image_fit.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner::client {
namespace {

constexpr int64_t kSimulation = 7;
// The newest state the store is told of, unless a test says otherwise.
constexpr int64_t kNewestState = 100;

// Sensor 0 a position sensor "Pos"; sensor 1 camera "Front", 64 x 48 with
// 16-bit depth; sensor 2 camera "Rear", 32 x 24, colour only.
model_t CameraModel() {
  model_t m{};
  m.simulation_id = kSimulation;
  auto sensor = [&](const std::string& name, int kind, std::vector<double> params) {
    sensor_t s{};
    s.id = static_cast<int32_t>(m.sensors.size());
    s.name = name;
    s.kind = static_cast<int8_t>(kind);
    s.body = 0;
    s.joint = -1;
    s.params = std::move(params);
    s.num_params = static_cast<int32_t>(s.params.size());
    m.sensors.push_back(s);
  };
  sensor("Pos", sensor_t::KIND_POSITION, {});
  sensor("Front", sensor_t::KIND_CAMERA, {64, 48, 1.0, 0.1, 50, 2});
  sensor("Rear", sensor_t::KIND_CAMERA, {32, 24, 1.0, 0.1, 50, 0});
  m.num_sensors = static_cast<int32_t>(m.sensors.size());
  return m;
}

// A well-formed image: bytes per pixel written out here, not taken from
// the code under test.
image_t Image(int camera, const std::string& name, int64_t step, int width, int height,
              int format = image_t::FORMAT_RGB8) {
  const int bytes_per_pixel = format == image_t::FORMAT_RGB8 ? 3 : format == image_t::FORMAT_DEPTH_F32 ? 4 : 2;
  image_t image{};
  image.simulation_id = kSimulation;
  image.step = step;
  image.sim_time = 0.001 * static_cast<double>(step);
  image.camera = camera;
  image.name = name;
  image.robot = "R";
  image.width = width;
  image.height = height;
  image.format = static_cast<int8_t>(format);
  image.num_bytes = width * height * bytes_per_pixel;
  image.data.assign(static_cast<size_t>(image.num_bytes), static_cast<uint8_t>(step));
  return image;
}

class ImageStoreTest : public ::testing::Test {
 protected:
  ImageStoreTest() {
    store_.SetModel(std::make_shared<const model_t>(CameraModel()));
    // Wired as the Client wires it: the subscription hands each datagram over.
    lcm_.subscribeFunction(
        channels::kImage,
        +[](const lcm::ReceiveBuffer* buffer, const std::string&, ImageStore* store) {
          store->Offer(buffer->data, buffer->data_size, kNewestState);
        },
        &store_);
  }
  void Send(const image_t& image) {
    ASSERT_EQ(lcm_.publish(channels::kImage, &image), 0);
    ASSERT_GT(lcm_.handleTimeout(1000), 0);
  }
  // Sends a forged image; it must be dropped with a description holding `words`.
  void ExpectDropped(const image_t& image, const std::string& words) {
    const uint64_t before = counter_.total();
    Send(image);
    EXPECT_EQ(counter_.total(), before + 1) << words;
    EXPECT_NE(counter_.last_description().find("SIM_IMAGE"), std::string::npos);
    EXPECT_NE(counter_.last_description().find(words), std::string::npos)
        << counter_.last_description();
  }

  lcm::LCM lcm_{"memq://"};
  BadMessageCounter counter_;
  std::vector<std::string> reports_;
  ImageStore store_{&counter_, [this](const std::string& m) { reports_.push_back(m); }};
};

TEST_F(ImageStoreTest, KeepsTheNewestColourAndDepthImageOfEachCamera) {
  EXPECT_FALSE(store_.Latest(1, ImageKind::kColour));
  EXPECT_EQ(store_.LatestStep(1, ImageKind::kColour), -1);
  Send(Image(1, "Front", 10, 64, 48));
  Send(Image(1, "Front", 10, 64, 48, image_t::FORMAT_DEPTH_U16));
  Send(Image(2, "Rear", 11, 32, 24));
  Send(Image(1, "Front", 20, 64, 48));
  ASSERT_TRUE(store_.Latest(1, ImageKind::kColour));
  EXPECT_EQ(store_.Latest(1, ImageKind::kColour)->step, 20);
  EXPECT_EQ(store_.Latest(1, ImageKind::kColour)->data.size(), 64u * 48u * 3u);
  EXPECT_EQ(store_.Latest(1, ImageKind::kDepth)->step, 10);
  EXPECT_EQ(store_.Latest(1, ImageKind::kDepth)->format, image_t::FORMAT_DEPTH_U16);
  EXPECT_EQ(store_.LatestStep(2, ImageKind::kColour), 11);
  EXPECT_FALSE(store_.Latest(2, ImageKind::kDepth));
  EXPECT_EQ(counter_.total(), 0u);
  EXPECT_TRUE(reports_.empty());
}

// simpartner-camera renders at the declared resolution: the audit's
// forged 64 x 64 image passed as the 640 x 480 camera's.
TEST_F(ImageStoreTest, AnImageSmallerThanDeclaredIsDropped) {
  ExpectDropped(Image(1, "Front", 3, 32, 24), "width 32: camera 'Front' is 64 wide");
  EXPECT_EQ(store_.LatestStep(1, ImageKind::kColour), -1);
}

// An image of a step no state has shown yet is held, not handed out: the
// audit's forged image stamped step 1e12 was printed as the camera's
// reading. When the state comes, the image held for it is kept.
TEST_F(ImageStoreTest, AnImageAheadOfTheStatesIsHeldUntilItsStateComes) {
  Send(Image(1, "Front", 90, 64, 48));
  Send(Image(1, "Front", 1000000000000, 64, 48));
  Send(Image(2, "Rear", 150, 32, 24));
  EXPECT_EQ(store_.LatestStep(1, ImageKind::kColour), 90);
  EXPECT_EQ(store_.LatestStep(2, ImageKind::kColour), -1);
  EXPECT_FALSE(store_.StateSeen(140));
  EXPECT_TRUE(store_.StateSeen(150));
  EXPECT_EQ(store_.LatestStep(2, ImageKind::kColour), 150);
  EXPECT_EQ(store_.LatestStep(1, ImageKind::kColour), 90);
  EXPECT_EQ(counter_.total(), 0u);
}

TEST_F(ImageStoreTest, ForgedImagesAreDroppedNamingTheFieldAndValue) {
  Send(Image(1, "Front", 10, 64, 48));
  ExpectDropped(Image(9, "Front", 30, 64, 48), "camera 9");
  ExpectDropped(Image(0, "Pos", 30, 64, 48), "'Pos' is not a camera");
  ExpectDropped(Image(1, "Back", 30, 64, 48), "name 'Back'");
  ExpectDropped(Image(1, "Front", 30, 64, 48, image_t::FORMAT_DEPTH_F32), "format 1");
  ExpectDropped(Image(2, "Rear", 30, 32, 24, image_t::FORMAT_DEPTH_U16), "format 2");
  ExpectDropped(Image(1, "Front", 30, 65, 48), "width 65");
  ExpectDropped(Image(1, "Front", 30, 64, 4096), "height 4096");
  ExpectDropped(Image(1, "Front", 30, 0, 48), "width 0");
  image_t format = Image(1, "Front", 30, 64, 48);
  format.format = 9;
  ExpectDropped(format, "format 9");
  // Width x height x 3 is not num_bytes (the data holds num_bytes).
  image_t short_data = Image(1, "Front", 30, 64, 48);
  short_data.num_bytes = 100;
  short_data.data.resize(100);
  ExpectDropped(short_data, "num_bytes 100");
  image_t claims_smaller = Image(1, "Front", 30, 10, 10);
  claims_smaller.num_bytes = 64 * 48 * 3;
  claims_smaller.data.resize(64 * 48 * 3);
  ExpectDropped(claims_smaller, "num_bytes 9216");
  // None of them replaced the image kept; the first drop was reported.
  EXPECT_EQ(store_.LatestStep(1, ImageKind::kColour), 10);
  EXPECT_FALSE(store_.Latest(1, ImageKind::kDepth));
  EXPECT_FALSE(store_.Latest(9, ImageKind::kColour));
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_NE(reports_[0].find("camera 9"), std::string::npos) << reports_[0];
}

TEST_F(ImageStoreTest, BytesThatDoNotDecodeAreRefused) {
  const std::vector<uint8_t> junk(40, 0xff);
  ASSERT_EQ(lcm_.publish(channels::kImage, junk.data(), static_cast<unsigned>(junk.size())), 0);
  ASSERT_GT(lcm_.handleTimeout(1000), 0);
  EXPECT_EQ(counter_.count(channels::kImage), 1u);
  ASSERT_EQ(reports_.size(), 1u);
  EXPECT_NE(reports_[0].find("SIM_IMAGE"), std::string::npos) << reports_[0];
}

TEST_F(ImageStoreTest, AnotherSimulationsImagesAreDroppedQuietly) {
  image_t other = Image(1, "Front", 10, 64, 48);
  other.simulation_id = kSimulation + 1;
  Send(other);
  EXPECT_FALSE(store_.Latest(1, ImageKind::kColour));
  EXPECT_EQ(counter_.total(), 0u);
}

TEST_F(ImageStoreTest, ANewModelDropsTheImagesKept) {
  Send(Image(1, "Front", 10, 64, 48));
  store_.SetModel(std::make_shared<const model_t>(CameraModel()));
  EXPECT_FALSE(store_.Latest(1, ImageKind::kColour));
  store_.SetModel(nullptr);
  Send(Image(1, "Front", 11, 64, 48));
  EXPECT_FALSE(store_.Latest(1, ImageKind::kColour));
  EXPECT_EQ(counter_.total(), 0u);
}

}  // namespace
}  // namespace simpartner::client
