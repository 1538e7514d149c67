// RGB images and PNG files (libpng): screenshots for tests and documents,
// camera images written by simpartner-cmd. A library of its own (sp_png),
// apart from sp_common: outside client projects should not need libpng.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "simpartner/image_t.hpp"

namespace simpartner {

// 8-bit RGB, rows top to bottom.
struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // width * height * 3

  struct Rgb {
    int r, g, b;
  };
  // Pixel (x, y) from the top-left; x, y are clamped into the image.
  Rgb At(int x, int y) const;
};

// Writing or reading a PNG failed (names the file and the reason).
class PngError : public std::runtime_error {
 public:
  explicit PngError(const std::string& what) : std::runtime_error(what) {}
};

void WritePng(const std::string& path, const RgbImage& image);
// 16-bit grey, rows top to bottom (width * height values).
void WriteGreyPng16(const std::string& path, int width, int height,
                    const std::vector<uint16_t>& values);
// A SIM_IMAGE message: colour as 8-bit RGB, depth as 16-bit grey in
// millimetres (float metres rounded; 0 where nothing is before far or
// beyond 65.535 m, as in FORMAT_DEPTH_U16). The image must fit its
// format (image_fit.h).
void WriteImagePng(const std::string& path, const image_t& image);
// Reads an 8-bit RGB or RGBA PNG (alpha dropped).
RgbImage ReadPng(const std::string& path);

}  // namespace simpartner
