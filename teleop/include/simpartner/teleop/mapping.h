// The teleop mapping file: which gamepad axes and buttons drive which
// actuators of a robot, one file per robot model (teleop/mappings/), and
// the plan built from it against a sim's model (targets resolved, wheel
// signs derived from the joint axes). Pure data, no transport, no SDL
// state (only SDL's axis and button names).
//
// Format: one statement per line, '#' starts a comment.
//   model <robot model name>        the robot file's name attribute
//   forward <body> <+x|-x|+y|-y|+z|-z>   the robot's forward direction: that
//                                   axis of the body's frame at step 0
//   deadman <button>                held: the robot may move
//   deadzone <0..0.9>               stick values below this count as 0
//   drive <axis> <scale>            wheel speed [rad/s] = scale * axis (-1..1)
//   wheel <actuator> [<max force>]  a velocity-controlled wheel
//   steer <axis> <actuator> <scale> <fmax> <P> <I> <D>
//                                   angle [rad] = scale * axis
//   level <name> <button +> <button -> <step> <min> <max> <fmax> <P> <I> <D>
//                                   a value changed by step per press
//   joint <level> <actuator> <factor>   angle [rad] = factor * level value
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "simpartner/client/catalog.h"
#include "simpartner/model_t.hpp"

namespace simpartner::teleop {

// "file:line: message" (line 0: the file as a whole).
struct Diagnostic {
  std::string file;
  int line = 0;
  std::string message;
  std::string ToString() const;
};
using Diagnostics = std::vector<Diagnostic>;
std::string JoinDiagnostics(const Diagnostics& diagnostics);

// Thrown when a mapping cannot be used; what() lists every diagnostic.
class MappingError : public std::runtime_error {
 public:
  explicit MappingError(Diagnostics diagnostics);
  const Diagnostics& diagnostics() const { return diagnostics_; }

 private:
  Diagnostics diagnostics_;
};

struct Gains {
  double fmax = 1000, p = 100, i = 0, d = 0;
};

struct Mapping {
  struct Wheel {
    int line = 0;
    std::string actuator;
    double max_force = 1000;
  };
  struct Steer {
    int line = 0;
    int axis = -1;  // SDL_GameControllerAxis
    std::string actuator;
    double scale = 0;
    Gains gains;
  };
  struct Level {
    int line = 0;
    std::string name;
    int button_plus = -1, button_minus = -1;  // SDL_GameControllerButton
    double step = 0, min = 0, max = 0;
    Gains gains;
  };
  struct Joint {
    int line = 0;
    std::string level, actuator;
    double factor = 0;
  };

  std::string file;
  std::string model;
  int model_line = 0;
  std::string forward_body;
  int forward_axis[3] = {1, 0, 0};  // in the body frame
  int forward_line = 0;
  int deadman_button = -1;
  int deadman_line = 0;
  double deadzone = 0.1;
  int drive_axis = -1;
  double drive_scale = 0;
  int drive_line = 0;
  std::vector<Wheel> wheels;
  std::optional<Steer> steer;
  std::vector<Level> levels;
  std::vector<Joint> joints;
};

// Parses mapping text; throws MappingError with every problem found
// (unknown statement, SDL axis or button name, bad number, missing
// deadman/drive/forward/wheel).
Mapping ParseMapping(const std::string& text, const std::string& file);
// Reads and parses; a file that cannot be read is a MappingError too.
Mapping LoadMapping(const std::string& path);

// The shipped mapping file for a robot model: "WorkPartner gen3" ->
// <dir>/workpartner_gen3.map.
std::string MappingFileFor(const std::string& model_name, const std::string& dir);

// A mapping resolved against a model.
struct Plan {
  struct Wheel {
    client::Target target;
    int sign = 1;  // +1: positive joint velocity rolls the robot forward
    double max_force = 1000;
  };
  struct Steer {
    client::Target target;
    int axis = -1;
    double scale = 0;
    Gains gains;
  };
  struct LevelJoint {
    client::Target target;
    double factor = 0;
  };
  struct Level {
    std::string name;
    int button_plus = -1, button_minus = -1;
    double step = 0, min = 0, max = 0;
    Gains gains;
    std::vector<LevelJoint> joints;
  };
  std::string mapping_file;
  std::string robot;  // robot instance driven
  int deadman_button = -1;
  double deadzone = 0.1;
  int drive_axis = -1;
  double drive_scale = 0;
  std::vector<Wheel> wheels;
  std::optional<Steer> steer;
  std::vector<Level> levels;
};

// Resolves every actuator of the mapping in the model's first robot whose
// model name the mapping names (or the first robot), checks the kinds
// (wheels velocity controllers, steer and joints angle controllers) and
// derives each wheel's sign from its joint axis, which body is the wheel
// and the forward direction. Throws MappingError naming file:line.
Plan BuildPlan(const Mapping& mapping, const model_t& model);

// The model_t a sim would announce for a world file (the fields the plan
// needs: robots, bodies' initial poses, joints' axes and bodies,
// actuators), for the offline --check. Throws std::runtime_error with the
// loader's diagnostics.
model_t ModelFromWorldFile(const std::string& world_path);

}  // namespace simpartner::teleop
