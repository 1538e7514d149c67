// Every rule of the checks of sensor readings, statuses, images, soil ruts,
// commands and replies (message_checks.h), one case each.
#include "simpartner/message_checks.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <vector>

#include "../support/non_finite.h"
#include "expect_problem.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner {
namespace {

using F = MessageFault;
using test_support::kInf;
using test_support::kNaN;
const std::string kBadUtf8("\xff\xfe", 2);

template <class Message>
struct MessageCase {
  const char* rule;
  std::function<void(Message*)> damage;
  const char* field;
  const char* message;
  MessageFault fault;
};

// Each case damages `good` and must be refused by `check`.
template <class Message, class Check>
void ExpectEachRefused(const Message& good, const std::vector<MessageCase<Message>>& cases,
                       const char* type, Check check) {
  ASSERT_FALSE(check(good)) << check(good)->message;
  for (const MessageCase<Message>& c : cases) {
    Message m = good;
    c.damage(&m);
    testing::ExpectProblem(check(m), c.rule, type, c.field, c.fault, c.message);
  }
}

ModelOutline ScannerAndCamera() {
  ModelOutline outline;
  outline.simulation_id = 5;
  outline.sensors = {{sensor_t::KIND_SCANNER, "Scanner"}, {sensor_t::KIND_CAMERA, "Eye"}};
  return outline;
}

sensor_reading_t GoodReading() {
  sensor_reading_t r{};
  r.simulation_id = 5;
  r.sensor = 0;
  r.kind = sensor_t::KIND_SCANNER;
  r.name = "Scanner";
  r.values = {1, 2, 3};
  r.num_values = 3;
  return r;
}

TEST(CheckSensorReading, RefusesEachBrokenRuleNamingTheField) {
  ExpectEachRefused<sensor_reading_t>(
      GoodReading(),
      {{"sim_time finite", [](sensor_reading_t* r) { r->sim_time = kNaN; }, "sim_time",
        "sim_time = nan", F::kNonFinite},
       {"values finite", [](sensor_reading_t* r) { r->values[1] = kInf; }, "values[1]",
        "values[1] = inf", F::kNonFinite},
       {"text", [](sensor_reading_t* r) { r->text = kBadUtf8; }, "text",
        "text is not valid UTF-8 of at most 65535 bytes", F::kBadText}},
      "sensor_reading_t", [](const sensor_reading_t& r) { return CheckSensorReading(r, nullptr); });
}

TEST(CheckSensorReading, RefusesWhatDoesNotFitItsModel) {
  const ModelOutline model = ScannerAndCamera();
  ExpectEachRefused<sensor_reading_t>(
      GoodReading(),
      {{"a sensor of the model", [](sensor_reading_t* r) { r->sensor = 3; }, "sensor",
        "sensor = 3 but the model of simulation 5 has 2 sensors", F::kBadIndex},
       {"of the sensor's kind", [](sensor_reading_t* r) { r->kind = sensor_t::KIND_IMU; },
        "kind", "kind = 5 but sensor 0 ('Scanner') of the model is of kind 2", F::kNotTheModels},
       {"of the sensor's name", [](sensor_reading_t* r) { r->name = "Lidar"; }, "name",
        "name = 'Lidar' but sensor 0 of the model is 'Scanner'", F::kNotTheModels}},
      "sensor_reading_t", [&](const sensor_reading_t& r) { return CheckSensorReading(r, &model); });
}

TEST(CheckStatus, RefusesEachBrokenRuleNamingTheField) {
  ExpectEachRefused<status_t>(
      status_t{},
      {{"sim_time finite", [](status_t* s) { s->sim_time = kInf; }, "sim_time", "sim_time = inf",
        F::kNonFinite},
       {"real_time_factor finite", [](status_t* s) { s->real_time_factor = kNaN; },
        "real_time_factor", "real_time_factor = nan", F::kNonFinite}},
      "status_t", CheckStatus);
}

// Camera "Eye" (sensor 1) of 4 x 2 pixels with a metres depth image.
model_t CameraModel() {
  model_t m{};
  sensor_t scanner{};
  scanner.name = "Scanner";
  scanner.kind = sensor_t::KIND_SCANNER;
  sensor_t eye{};
  eye.name = "Eye";
  eye.kind = sensor_t::KIND_CAMERA;
  eye.params = {4, 2, 1.0, 0.1, 50, image_t::FORMAT_DEPTH_F32};
  eye.num_params = 6;
  m.sensors = {scanner, eye};
  m.num_sensors = 2;
  return m;
}

image_t GoodImage() {
  image_t image{};
  image.camera = 1;
  image.name = "Eye";
  image.width = 4;
  image.height = 2;
  image.format = image_t::FORMAT_RGB8;
  image.data.assign(24, 0);
  image.num_bytes = 24;
  return image;
}

TEST(CheckImage, RefusesEachBrokenRuleNamingTheField) {
  ExpectEachRefused<image_t>(
      GoodImage(),
      {{"a known format", [](image_t* i) { i->format = 9; }, "format",
        "format 9: not an image_t.FORMAT_*", F::kUnknownValue},
       {"width 1 to 4096", [](image_t* i) { i->width = 0; }, "width", "width 0: 1 to 4096 pixels",
        F::kOutOfRange},
       {"height 1 to 4096", [](image_t* i) { i->height = 5000; }, "height",
        "height 5000: 1 to 4096 pixels", F::kOutOfRange},
       {"num_bytes width x height x bytes per pixel",
        [](image_t* i) {
          i->data.resize(29);
          i->num_bytes = 29;
        },
        "num_bytes", "num_bytes 29: 4x2 rgb8 is 24 bytes", F::kCountMismatch}},
      "image_t", [](const image_t& i) { return CheckImage(i, nullptr); });
}

TEST(CheckImage, RefusesWhatDoesNotFitTheModelsCamera) {
  const model_t model = CameraModel();
  ExpectEachRefused<image_t>(
      GoodImage(),
      {{"a sensor of the model", [](image_t* i) { i->camera = 9; }, "camera",
        "camera 9: the model has 2 sensors", F::kBadIndex},
       {"a camera", [](image_t* i) { i->camera = 0; }, "camera",
        "camera 0: sensor 'Scanner' is not a camera", F::kNotTheModels},
       {"the camera's name", [](image_t* i) { i->name = "Rear"; }, "name",
        "name 'Rear': camera 1 is 'Eye'", F::kNotTheModels},
       {"the camera's depth format",
        [](image_t* i) {
          i->format = image_t::FORMAT_DEPTH_U16;
          i->data.resize(16);
          i->num_bytes = 16;
        },
        "format", "format 2: camera 'Eye' has depth-f32", F::kNotTheModels},
       {"the camera's width",
        [](image_t* i) {
          i->width = 5;
          i->data.resize(30);
          i->num_bytes = 30;
        },
        "width", "width 5: camera 'Eye' is 4 wide", F::kNotTheModels},
       {"the camera's height",
        [](image_t* i) {
          i->height = 3;
          i->data.resize(36);
          i->num_bytes = 36;
        },
        "height", "height 3: camera 'Eye' is 2 high", F::kNotTheModels},
       // The audit's forged 64 x 64 image passed as the 640 x 480 camera's.
       {"the camera's width, not less",
        [](image_t* i) {
          i->width = 1;
          i->data.resize(6);
          i->num_bytes = 6;
        },
        "width", "width 1: camera 'Eye' is 4 wide", F::kNotTheModels}},
      "image_t", [&](const image_t& i) { return CheckImage(i, &model); });
}

soil_ruts_t GoodRuts() {
  soil_ruts_t r{};
  r.parts = 1;
  r.up[1] = 1;
  r.u_axis[0] = 1;
  r.cell_size = 0.02;
  r.u = {3};
  r.w = {4};
  r.depth = {0.01f};
  r.num_cells = 1;
  return r;
}

TEST(CheckSoilRuts, RefusesEachBrokenRuleNamingTheField) {
  ExpectEachRefused<soil_ruts_t>(
      GoodRuts(),
      {{"part within parts", [](soil_ruts_t* r) { r->part = 1; }, "part",
        "part = 1 of parts = 1", F::kOutOfRange},
       {"origin finite", [](soil_ruts_t* r) { r->origin[0] = kNaN; }, "origin",
        "origin = (nan, 0, 0)", F::kNonFinite},
       {"up unit", [](soil_ruts_t* r) { r->up[1] = 2; }, "up",
        "up = (0, 2, 0) is not a unit vector", F::kNotUnit},
       {"u_axis unit", [](soil_ruts_t* r) { r->u_axis[0] = 0.5; }, "u_axis",
        "u_axis = (0.5, 0, 0) is not a unit vector", F::kNotUnit},
       {"u_axis along the surface",
        [](soil_ruts_t* r) {
          r->u_axis[0] = 0;
          r->u_axis[1] = 1;
        },
        "u_axis", "u_axis = (0, 1, 0) is not along the surface of up = (0, 1, 0)",
        F::kOutOfRange},
       {"cell_size 1 mm to 1 m", [](soil_ruts_t* r) { r->cell_size = 0; }, "cell_size",
        "cell_size = 0 (1 mm to 1 m)", F::kOutOfRange},
       {"a known ground", [](soil_ruts_t* r) { r->ground = 2; }, "ground",
        "ground = 2 (0 the plane, 1 the heightfield)", F::kUnknownValue},
       {"depth above 0 and at most 10 m", [](soil_ruts_t* r) { r->depth[0] = -0.5f; },
        "depth[0]", "depth[0] = -0.5 (cell 3, 4; 0 < depth <= 10 m)", F::kOutOfRange}},
      "soil_ruts_t", CheckSoilRuts);
}

TEST(CheckCommand, RefusesEachBrokenTextNamingTheField) {
  command_t good{};
  good.sender = "cmd@host:1";
  ExpectEachRefused<command_t>(
      good,
      {{"sender text", [](command_t* c) { c->sender = kBadUtf8; }, "sender",
        "sender is not valid UTF-8 of at most 255 bytes", F::kBadText},
       {"robot text", [](command_t* c) { c->robot = std::string(256, 'r'); }, "robot",
        "robot is not valid UTF-8 of at most 255 bytes (256 bytes)", F::kBadText},
       {"target text", [](command_t* c) { c->target = kBadUtf8; }, "target",
        "target is not valid UTF-8", F::kBadText},
       {"text", [](command_t* c) { c->text = kBadUtf8; }, "text",
        "text is not valid UTF-8 of at most 65535 bytes", F::kBadText}},
      "command_t", CheckCommand);
}

TEST(CheckCommandReply, RefusesEachBrokenTextNamingTheField) {
  ExpectEachRefused<command_reply_t>(
      command_reply_t{},
      {{"sender text", [](command_reply_t* r) { r->sender = kBadUtf8; }, "sender",
        "sender is not valid UTF-8 of at most 255 bytes", F::kBadText},
       {"target text", [](command_reply_t* r) { r->target = kBadUtf8; }, "target",
        "target is not valid UTF-8", F::kBadText},
       {"reason text", [](command_reply_t* r) { r->reason = kBadUtf8; }, "reason",
        "reason is not valid UTF-8 of at most 65535 bytes", F::kBadText},
       {"previous_text", [](command_reply_t* r) { r->previous_text = kBadUtf8; },
        "previous_text", "previous_text is not valid UTF-8", F::kBadText}},
      "command_reply_t", CheckCommandReply);
}

}  // namespace
}  // namespace simpartner
