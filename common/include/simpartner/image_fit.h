// The pixel formats of camera images (image_t on SIM_IMAGE). Whether an
// image may be taken is CheckImage's (message_checks.h).
#pragma once

namespace simpartner {

// Bytes of one pixel of image_t.FORMAT_*: 3 (RGB8), 4 (DEPTH_F32),
// 2 (DEPTH_U16); 0 for a format image_t does not define.
int ImageBytesPerPixel(int format);

// The word for image_t.FORMAT_*: "rgb8", "depth-f32", "depth-u16", or
// "unknown".
const char* ImageFormatName(int format);

}  // namespace simpartner
