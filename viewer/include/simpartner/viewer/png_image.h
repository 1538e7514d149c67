// RGB images and PNG files (libpng): screenshots for tests and documents.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner::viewer {

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
// Reads an 8-bit RGB or RGBA PNG (alpha dropped).
RgbImage ReadPng(const std::string& path);

}  // namespace simpartner::viewer
