// simpartner-teleop's command line (and its test build's, with the virtual
// pad's script): the options RunTeleop runs with, and the offline --check
// of a mapping against a world.
#pragma once

#include <iosfwd>
#include <string>

#include "simpartner/command_line.h"
#include "simpartner/teleop/session.h"

namespace simpartner::teleop {

enum class TeleopInput { kGamepad, kKeyboard };

struct TeleopOptions {
  SessionOptions session;  // bus, mapping, speed overrides
  TeleopInput input = TeleopInput::kGamepad;  // --input gamepad|keyboard
  bool list = false;        // --list: name the connected controllers and exit
  bool check = false;       // --check: the mapping against --environment, offline
  std::string environment;  // --environment WORLD
  std::string script;       // the virtual pad's script file ("" = stdin)
};

// What the program takes on its command line; virtual_pad: the test build
// simpartner-teleop-vpad, which also takes --script FILE.
CommandLineSpec TeleopCommandLine(bool virtual_pad);

// The options of a command line ParseCommandLine accepted.
TeleopOptions MakeTeleopOptions(const CommandLine& command_line, bool virtual_pad);

// --check: does the mapping (--mapping, else the shipped one for the
// robot's model) fit the first robot of --environment? Writes the answer;
// returns 0 when it fits, 1 when not.
int CheckMapping(const TeleopOptions& options, std::ostream& out, std::ostream& err);

}  // namespace simpartner::teleop
