#include <tuple>
#include <utility>

#include "message_rules.h"
#include "simpartner/image_fit.h"
#include "simpartner/message_checks.h"
#include "simpartner/sensor_t.hpp"

namespace simpartner {
namespace {

using message_rules::MessageRules;

// image_t.lcm: width and height at most 4096.
constexpr int32_t kMaxSide = 4096;
// sensor_t.params of a camera: width, height, fov, near, far, depth.
constexpr size_t kWidthParam = 0;
constexpr size_t kHeightParam = 1;
constexpr size_t kDepthParam = 5;

double Param(const sensor_t& camera, size_t k) {
  return camera.params.size() > k ? camera.params[k] : 0.0;
}

// A known format, sides of 1 to kMaxSide, and num_bytes (and the data)
// what they make.
MessageCheck CheckPixels(const image_t& image, const MessageRules& rules) {
  const int bytes_per_pixel = ImageBytesPerPixel(image.format);
  if (bytes_per_pixel == 0)
    return rules.Problem(MessageFault::kUnknownValue, "format",
                         " " + std::to_string(image.format) + ": not an image_t.FORMAT_*");
  for (const auto& [field, side] :
       {std::pair<const char*, int32_t>{"width", image.width}, {"height", image.height}})
    if (side < 1 || side > kMaxSide)
      return rules.Problem(MessageFault::kOutOfRange, field,
                           " " + std::to_string(side) + ": 1 to " + std::to_string(kMaxSide) +
                               " pixels");
  const int64_t expected = static_cast<int64_t>(image.width) * image.height * bytes_per_pixel;
  if (image.num_bytes != expected || image.data.size() != static_cast<size_t>(image.num_bytes))
    return rules.Problem(MessageFault::kCountMismatch, "num_bytes",
                         " " + std::to_string(image.num_bytes) + ": " +
                             std::to_string(image.width) + "x" + std::to_string(image.height) +
                             " " + ImageFormatName(image.format) + " is " +
                             std::to_string(expected) + " bytes");
  return std::nullopt;
}

// The camera index is a camera sensor of the model with the image's name,
// the format colour or the camera's depth format, and the sides the
// camera's declared resolution (simpartner-camera renders at it or does
// not start).
MessageCheck CheckFitsCamera(const image_t& image, const model_t& model,
                             const MessageRules& rules) {
  if (image.camera < 0 || static_cast<size_t>(image.camera) >= model.sensors.size())
    return rules.Problem(MessageFault::kBadIndex, "camera",
                         " " + std::to_string(image.camera) + ": the model has " +
                             std::to_string(model.sensors.size()) + " sensors");
  const sensor_t& camera = model.sensors[static_cast<size_t>(image.camera)];
  if (camera.kind != sensor_t::KIND_CAMERA)
    return rules.Problem(MessageFault::kNotTheModels, "camera",
                         " " + std::to_string(image.camera) + ": sensor '" + camera.name +
                             "' is not a camera");
  if (camera.name != image.name)
    return rules.Problem(MessageFault::kNotTheModels, "name",
                         " '" + image.name + "': camera " + std::to_string(image.camera) +
                             " is '" + camera.name + "'");
  const int depth = static_cast<int>(Param(camera, kDepthParam));
  if (image.format != image_t::FORMAT_RGB8 && image.format != depth)
    return rules.Problem(MessageFault::kNotTheModels, "format",
                         " " + std::to_string(image.format) + ": camera '" + camera.name +
                             "' has " +
                             (depth == 0 ? std::string("no depth") : ImageFormatName(depth)));
  for (const auto& [field, side, param, word] :
       {std::tuple<const char*, int32_t, size_t, const char*>{"width", image.width, kWidthParam,
                                                              " wide"},
        {"height", image.height, kHeightParam, " high"}}) {
    const int64_t declared = static_cast<int64_t>(Param(camera, param));
    if (side != declared)
      return rules.Problem(MessageFault::kNotTheModels, field,
                           " " + std::to_string(side) + ": camera '" + camera.name + "' is " +
                               std::to_string(declared) + word);
  }
  return std::nullopt;
}

}  // namespace

MessageCheck CheckImage(const image_t& image, const model_t* model) {
  const MessageRules rules("image_t");
  if (auto bad = CheckPixels(image, rules)) return bad;
  if (model) return CheckFitsCamera(image, *model, rules);
  return std::nullopt;
}

}  // namespace simpartner
