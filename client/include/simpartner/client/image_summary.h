// One line about a camera image for people (simpartner-cmd read CAMERA):
// its size and format, and what it shows in numbers.
#pragma once

#include <string>

#include "simpartner/image_t.hpp"

namespace simpartner::client {

// "64x48 rgb8, mean colour 120.5 130.2 90.1" (red green blue, 0 to 255);
// "64x48 depth-u16, depth 1.234 to 5.678 m, 12 of 3072 pixels see nothing"
// (min and max of the pixels that see something: finite for depth-f32,
// not 0 for depth-u16). The image must fit its format (image_fit.h).
std::string SummariseImage(const image_t& image);

}  // namespace simpartner::client
