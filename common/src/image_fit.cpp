#include "simpartner/image_fit.h"

#include "simpartner/sensor_t.hpp"

namespace simpartner {
namespace {

// sensor_t.params of a camera: width, height, fov, near, far, depth.
constexpr size_t kWidthParam = 0;
constexpr size_t kHeightParam = 1;
constexpr size_t kDepthParam = 5;

std::string Field(const char* field, int64_t value) {
  return std::string(field) + " " + std::to_string(value);
}

double Param(const sensor_t& camera, size_t k) {
  return camera.params.size() > k ? camera.params[k] : 0.0;
}

}  // namespace

int ImageBytesPerPixel(int format) {
  switch (format) {
    case image_t::FORMAT_RGB8: return 3;
    case image_t::FORMAT_DEPTH_F32: return 4;
    case image_t::FORMAT_DEPTH_U16: return 2;
    default: return 0;
  }
}

const char* ImageFormatName(int format) {
  switch (format) {
    case image_t::FORMAT_RGB8: return "rgb8";
    case image_t::FORMAT_DEPTH_F32: return "depth-f32";
    case image_t::FORMAT_DEPTH_U16: return "depth-u16";
    default: return "unknown";
  }
}

std::optional<std::string> ImageMisfit(const image_t& image, const model_t& model) {
  if (image.camera < 0 || static_cast<size_t>(image.camera) >= model.sensors.size())
    return Field("camera", image.camera) + ": the model has " +
           std::to_string(model.sensors.size()) + " sensors";
  const sensor_t& camera = model.sensors[static_cast<size_t>(image.camera)];
  if (camera.kind != sensor_t::KIND_CAMERA)
    return Field("camera", image.camera) + ": sensor '" + camera.name + "' is not a camera";
  if (camera.name != image.name)
    return "name '" + image.name + "': camera " + std::to_string(image.camera) + " is '" +
           camera.name + "'";
  const int bytes_per_pixel = ImageBytesPerPixel(image.format);
  if (bytes_per_pixel == 0) return Field("format", image.format) + ": not an image_t.FORMAT_*";
  const int depth = static_cast<int>(Param(camera, kDepthParam));
  if (image.format != image_t::FORMAT_RGB8 && image.format != depth)
    return Field("format", image.format) + ": camera '" + camera.name + "' has " +
           (depth == 0 ? std::string("no depth") : std::string(ImageFormatName(depth)));
  const int64_t max_width = static_cast<int64_t>(Param(camera, kWidthParam));
  const int64_t max_height = static_cast<int64_t>(Param(camera, kHeightParam));
  if (image.width < 1 || image.width > max_width)
    return Field("width", image.width) + ": camera '" + camera.name + "' is " +
           std::to_string(max_width) + " wide";
  if (image.height < 1 || image.height > max_height)
    return Field("height", image.height) + ": camera '" + camera.name + "' is " +
           std::to_string(max_height) + " high";
  const int64_t expected = static_cast<int64_t>(image.width) * image.height * bytes_per_pixel;
  if (image.num_bytes != expected || image.data.size() != static_cast<size_t>(image.num_bytes))
    return Field("num_bytes", image.num_bytes) + ": " + std::to_string(image.width) + "x" +
           std::to_string(image.height) + " " + ImageFormatName(image.format) + " is " +
           std::to_string(expected) + " bytes";
  return std::nullopt;
}

}  // namespace simpartner
