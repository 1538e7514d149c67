#include "simpartner/png_image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

namespace simpartner {
namespace {

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<FILE, FileCloser>;

// libpng reports errors by longjmp to the setjmp of the function that
// called it; the message is kept here. The functions that call setjmp
// construct no C++ object after it, so the jump skips no destructor.
struct PngErrorText {
  char text[256] = "libpng error";
};

[[noreturn]] void OnPngError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngErrorText*>(png_get_error_ptr(png));
  std::snprintf(sink->text, sizeof sink->text, "%s", message);
  png_longjmp(png, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}

// What WriteRows writes: rows of `row_bytes` bytes, top to bottom, as
// libpng takes them (16-bit samples big-endian).
struct PngRows {
  int width = 0, height = 0;
  int bit_depth = 8;
  int colour_type = PNG_COLOR_TYPE_RGB;
  const uint8_t* data = nullptr;
  size_t row_bytes = 0;
};

// Returns nullptr on success, else the error text.
const char* WriteRows(FILE* file, const PngRows& rows, PngErrorText* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, OnPngError, OnPngWarning);
  if (png == nullptr) return "libpng cannot start";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return "libpng cannot start";
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return error->text;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(rows.width),
               static_cast<png_uint_32>(rows.height), rows.bit_depth, rows.colour_type,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < rows.height; ++y)
    png_write_row(png, rows.data + static_cast<size_t>(y) * rows.row_bytes);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return nullptr;
}

void WriteFile(const std::string& path, const PngRows& rows) {
  File file(std::fopen(path.c_str(), "wb"));
  if (!file) throw PngError(path + ": cannot write: " + std::strerror(errno));
  PngErrorText error;
  if (const char* problem = WriteRows(file.get(), rows, &error))
    throw PngError(path + ": " + problem);
  if (std::fflush(file.get()) != 0) throw PngError(path + ": cannot write: " + std::strerror(errno));
}

// A depth sample as millimetres of FORMAT_DEPTH_U16.
uint16_t Millimetres(const image_t& image, size_t i) {
  if (image.format == image_t::FORMAT_DEPTH_U16)
    return static_cast<uint16_t>(image.data[2 * i] | (image.data[2 * i + 1] << 8));
  float metres;
  std::memcpy(&metres, image.data.data() + 4 * i, sizeof metres);
  const double mm = std::round(static_cast<double>(metres) * 1000.0);
  return std::isfinite(mm) && mm > 0 && mm <= 65535 ? static_cast<uint16_t>(mm) : 0;
}

const char* ReadRows(FILE* file, RgbImage* image, PngErrorText* error) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, OnPngError, OnPngWarning);
  if (png == nullptr) return "libpng cannot start";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    return "libpng cannot start";
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return error->text;
  }
  png_init_io(png, file);
  png_read_info(png, info);
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_strip_alpha(png);
  png_set_gray_to_rgb(png);
  png_read_update_info(png, info);
  image->width = static_cast<int>(png_get_image_width(png, info));
  image->height = static_cast<int>(png_get_image_height(png, info));
  if (png_get_rowbytes(png, info) != static_cast<size_t>(image->width) * 3) {
    png_destroy_read_struct(&png, &info, nullptr);
    return "not convertible to 8-bit RGB";
  }
  image->pixels.resize(static_cast<size_t>(image->width) * image->height * 3);
  for (int y = 0; y < image->height; ++y)
    png_read_row(png, image->pixels.data() + static_cast<size_t>(y) * image->width * 3, nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return nullptr;
}

}  // namespace

RgbImage::Rgb RgbImage::At(int x, int y) const {
  x = std::clamp(x, 0, width - 1);
  y = std::clamp(y, 0, height - 1);
  const size_t i = (static_cast<size_t>(y) * width + x) * 3;
  return {pixels[i], pixels[i + 1], pixels[i + 2]};
}

void WritePng(const std::string& path, const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != static_cast<size_t>(image.width) * image.height * 3)
    throw PngError(path + ": image is " + std::to_string(image.width) + " x " +
                   std::to_string(image.height) + " with " + std::to_string(image.pixels.size()) +
                   " bytes");
  WriteFile(path, PngRows{image.width, image.height, 8, PNG_COLOR_TYPE_RGB, image.pixels.data(),
                          static_cast<size_t>(image.width) * 3});
}

void WriteGreyPng16(const std::string& path, int width, int height,
                    const std::vector<uint16_t>& values) {
  if (width <= 0 || height <= 0 || values.size() != static_cast<size_t>(width) * height)
    throw PngError(path + ": grey image is " + std::to_string(width) + " x " +
                   std::to_string(height) + " with " + std::to_string(values.size()) + " values");
  std::vector<uint8_t> big_endian(2 * values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    big_endian[2 * i] = static_cast<uint8_t>(values[i] >> 8);
    big_endian[2 * i + 1] = static_cast<uint8_t>(values[i] & 0xff);
  }
  WriteFile(path, PngRows{width, height, 16, PNG_COLOR_TYPE_GRAY, big_endian.data(),
                          static_cast<size_t>(width) * 2});
}

void WriteImagePng(const std::string& path, const image_t& image) {
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.format == image_t::FORMAT_RGB8) {
    RgbImage rgb{image.width, image.height, std::vector<uint8_t>(image.data.begin(), image.data.end())};
    WritePng(path, rgb);
    return;
  }
  const size_t bytes = image.format == image_t::FORMAT_DEPTH_F32 ? 4 : 2;
  if (image.data.size() != pixels * bytes)
    throw PngError(path + ": depth image is " + std::to_string(image.width) + " x " +
                   std::to_string(image.height) + " with " + std::to_string(image.data.size()) +
                   " bytes");
  std::vector<uint16_t> mm(pixels);
  for (size_t i = 0; i < pixels; ++i) mm[i] = Millimetres(image, i);
  WriteGreyPng16(path, image.width, image.height, mm);
}

RgbImage ReadPng(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw PngError(path + ": cannot read: " + std::strerror(errno));
  RgbImage image;
  PngErrorText error;
  if (const char* problem = ReadRows(file.get(), &image, &error))
    throw PngError(path + ": " + problem);
  return image;
}

}  // namespace simpartner
