// Whether a camera image (image_t on SIM_IMAGE) fits the model it claims to
// come from: one check for every reader of images, so a forged or broken
// image is told apart the same way everywhere.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "simpartner/image_t.hpp"
#include "simpartner/model_t.hpp"

namespace simpartner {

// Bytes of one pixel of image_t.FORMAT_*: 3 (RGB8), 4 (DEPTH_F32),
// 2 (DEPTH_U16); 0 for a format image_t does not define.
int ImageBytesPerPixel(int format);

// The word for image_t.FORMAT_*: "rgb8", "depth-f32", "depth-u16", or
// "unknown".
const char* ImageFormatName(int format);

// Why `image` does not fit `model`, naming the field and its value
// ("camera 7: the model has 3 sensors"), or nothing when it fits: the
// camera index is a camera sensor of the model with the image's name, the
// format is colour or the camera's declared depth format, width and height
// are 1 to the camera's declared resolution, and num_bytes is width x
// height x bytes per pixel. The simulation id is the caller's to check.
std::optional<std::string> ImageMisfit(const image_t& image, const model_t& model);

}  // namespace simpartner
