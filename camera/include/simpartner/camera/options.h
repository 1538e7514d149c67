// simpartner-camera's command line: its options besides the parameters (of
// which it reads lcmUrl), and the options built from both.
#pragma once

#include <string>

#include "simpartner/command_line.h"

namespace simpartner::camera {

struct CameraOptions {
  std::string lcm_url;
  double quit_after = 0;  // [s] exit after this long (0 = never); prints frame figures
  std::string save_dir;   // write each camera's last frame here as NAME.png when it exits ("" = none;
                          // characters other than letters, digits, - and _ in NAME become _)
};

CommandLineSpec CameraCommandLine();
// Throws ConfigError naming the flag and value.
CameraOptions MakeCameraOptions(const CommandLine& command_line, const Parameters& params);

}  // namespace simpartner::camera
