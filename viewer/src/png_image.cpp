#include "simpartner/viewer/png_image.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>

namespace simpartner::viewer {
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

// Returns nullptr on success, else the error text.
const char* WriteRows(FILE* file, const RgbImage& image, PngErrorText* error) {
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
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y)
    png_write_row(png, image.pixels.data() + static_cast<size_t>(y) * image.width * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return nullptr;
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
  File file(std::fopen(path.c_str(), "wb"));
  if (!file) throw PngError(path + ": cannot write: " + std::strerror(errno));
  PngErrorText error;
  if (const char* problem = WriteRows(file.get(), image, &error))
    throw PngError(path + ": " + problem);
  if (std::fflush(file.get()) != 0) throw PngError(path + ": cannot write: " + std::strerror(errno));
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

}  // namespace simpartner::viewer
