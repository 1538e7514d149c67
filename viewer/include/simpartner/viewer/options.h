// simpartner-viewer's command line: its options besides the parameters (of
// which it reads lcmUrl), and the viewer options built from both.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/viewer/camera.h"
#include "simpartner/viewer/toggles.h"

namespace simpartner::viewer {

// An explicit camera: target, yaw and pitch [deg], distance [m].
struct CameraSpec {
  double target[3] = {0, 0, 0};
  double yaw_deg = 0;
  double pitch_deg = 0;
  double distance = 5;
};

struct ViewerOptions {
  std::string lcm_url;
  int width = 1280;
  int height = 720;
  double max_fps = 60;       // 0: as fast as it can draw
  std::string screenshot;    // write this PNG, then exit ("" = run until closed)
  double after_seconds = 0;  // screenshot this long after start...
  int64_t after_frames = 0;  // ...or after this many frames
  double quit_after = 0;     // [s] exit after this long (0 = never); prints frame figures
  std::optional<CameraSpec> camera;  // fixed start camera (turns follow off)
  Toggles toggles;
  std::string camera_image;  // camera sensor whose image (SIM_IMAGE) the inset shows ("" = none)
  double scanner_poll_hz = 0;  // ask scanners for readings this often (0 = only listen)
  int nice = 5;                // lower the viewer's CPU priority by this much (0..19)
};

// What simpartner-viewer takes on its command line.
CommandLineSpec ViewerCommandLine();
// Throws ConfigError naming the flag and value.
ViewerOptions MakeViewerOptions(const CommandLine& command_line, const Parameters& params);
// Camera for a spec in a world with `up`.
Camera CameraFromSpec(const CameraSpec& spec, const Eigen::Vector3d& up);

}  // namespace simpartner::viewer
