// The viewer program: an SDL2 window with an OpenGL context, the bus, the
// scene and the camera, run frame by frame at the display's pace (or
// --fps), independent of how fast the sim steps.
#pragma once

#include <iosfwd>

#include "simpartner/viewer/options.h"

namespace simpartner::viewer {

// Runs until the window closes, Esc, SIGINT/SIGTERM, --quit-after or the
// --screenshot is written. Progress and problems go to `out` / `err`.
// Returns the exit status; throws std::runtime_error when SDL, OpenGL or
// LCM cannot start (naming which and why).
int RunViewer(const ViewerOptions& options, std::ostream& out, std::ostream& err);

}  // namespace simpartner::viewer
