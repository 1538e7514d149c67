#include "simpartner/image_fit.h"

#include "simpartner/image_t.hpp"

namespace simpartner {

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

}  // namespace simpartner
