// simpartner-cmd: the bus from a shell (like `ros2 topic pub`). The whole
// program is this function, so tests run it in-process against a real sim.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/image_t.hpp"

namespace simpartner::client {

// Exit statuses of simpartner-cmd; each names one outcome.
enum CmdExit : int {
  kCmdOk = 0,          // accepted / done
  kCmdRefused = 1,     // the sim answered: not accepted (its reason is printed)
  kCmdUsage = 2,       // bad command line or values (nothing was sent)
  kCmdNoAnswer = 3,    // no sim on the bus, or no reply in time
  kCmdUnknownName = 4, // a name or port the model does not have
  kCmdRestarted = 5,   // the sim restarted while we talked to it
  kCmdFileError = 6,   // read --out: the image came but its file could not be written
};

// Writes a camera's image to a file (read CAMERA --out FILE); throws
// std::exception with the file and the reason. simpartner-cmd passes one
// that writes PNG (common/png_image.h): the client library itself does not
// link libpng.
using ImageFileWriter = std::function<void(const std::string& path, const image_t& image)>;

// args without the program name, e.g. {"set", "Axle1Motor", "300,1.0"}.
// Without `write_image`, read --out is refused as unavailable.
int RunCmd(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
           const ImageFileWriter& write_image = {});

// What simpartner-cmd takes on its command line: a command and its
// arguments, --timeout, and the bus as the other programs read it.
CommandLineSpec CmdCommandLine();

}  // namespace simpartner::client
