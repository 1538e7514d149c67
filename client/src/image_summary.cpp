#include "simpartner/client/image_summary.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "simpartner/image_fit.h"
#include "simpartner/text.h"

namespace simpartner::client {
namespace {

std::string MeanColour(const image_t& image) {
  double sum[3] = {0, 0, 0};
  const size_t pixels = image.data.size() / 3;
  for (size_t i = 0; i < pixels; ++i)
    for (size_t c = 0; c < 3; ++c) sum[c] += image.data[3 * i + c];
  std::string out = "mean colour";
  for (double s : sum) out += " " + FormatFixed(pixels ? s / static_cast<double>(pixels) : 0.0, 1);
  return out;
}

// Depth of pixel i in metres; NaN when it sees nothing before far.
double DepthAt(const image_t& image, size_t i) {
  if (image.format == image_t::FORMAT_DEPTH_F32) {
    float metres;
    std::memcpy(&metres, image.data.data() + 4 * i, sizeof metres);  // little-endian
    return std::isfinite(metres) ? metres : std::nan("");
  }
  uint16_t millimetres;
  std::memcpy(&millimetres, image.data.data() + 2 * i, sizeof millimetres);
  return millimetres == 0 ? std::nan("") : millimetres / 1000.0;
}

std::string DepthRange(const image_t& image) {
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  size_t nothing = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const double d = DepthAt(image, i);
    if (std::isnan(d)) {
      ++nothing;
      continue;
    }
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  std::string out = nothing == pixels ? std::string("no depth")
                                      : "depth " + FormatFixed(lo, 3) + " to " +
                                            FormatFixed(hi, 3) + " m";
  return out + ", " + std::to_string(nothing) + " of " + std::to_string(pixels) +
         " pixels see nothing";
}

}  // namespace

std::string SummariseImage(const image_t& image) {
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height) +
                           " " + ImageFormatName(image.format) + ", ";
  return size + (image.format == image_t::FORMAT_RGB8 ? MeanColour(image) : DepthRange(image));
}

}  // namespace simpartner::client
