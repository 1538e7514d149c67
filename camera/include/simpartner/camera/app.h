// The simpartner-camera program: a hidden window for the GL context, the
// viewer's bus and scene, and an offscreen renderer. Each state the scene
// accepts is offered to every camera of the model; a camera whose frame is
// due renders it at once, while it is the scene's newest, and publishes
// the images on SIM_IMAGE stamped with that state's step.
#pragma once

#include <iosfwd>

#include "simpartner/camera/options.h"

namespace simpartner::camera {

// Runs until SIGINT/SIGTERM or --quit-after; prints per-camera figures
// (frames rendered and due, latency) to `out` and problems to `err`.
// Returns the exit status; throws std::runtime_error when SDL, OpenGL or
// LCM cannot start (naming which and why).
int RunCamera(const CameraOptions& options, std::ostream& out, std::ostream& err);

}  // namespace simpartner::camera
