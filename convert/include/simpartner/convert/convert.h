// simpartner-convert: the direction comes from the input's kind.
//   URDF (<robot> with <link>s)    -> our robot XML
//   our world XML (<world>)        -> MJCF (the world, its robots, objects)
//   our robot XML (<robot> with <body>s) -> MJCF (the robot alone, no ground)
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/command_line.h"
#include "simpartner/parameters.h"

namespace simpartner::convert {

enum class InputKind { kUrdf, kRobot, kWorld };

// The kind of an XML text by its root element; throws ConvertError
// (file:line) for a file that is not well-formed or none of the three.
InputKind DetectInputKind(const std::string& text, const std::string& file_name);

struct ConvertRequest {
  std::string input;
  std::string output;
  bool mesh_as_box = false;
  Parameters params;              // step size and contact defaults for MJCF
};

struct ConvertOutcome {
  InputKind kind = InputKind::kUrdf;
  std::string text;               // what was written to the output
  std::vector<std::string> notes; // conversions worth telling (and what was left out)
};

// Reads, converts and writes; throws ConvertError, ModelError or Error.
ConvertOutcome Convert(const ConvertRequest& request);

// What simpartner-convert takes on its command line.
CommandLineSpec ConvertCommandLine();

// The program: arguments without argv[0]. Returns the exit status (0 done,
// 1 bad input, 2 bad usage).
int RunConvert(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace simpartner::convert
