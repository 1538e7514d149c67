// The input side of teleop: SDL2's GameController API with hot-plug, a
// small keyboard window, the test build's virtual pad driven by a script,
// and the program around them (RunTeleop), so that main.cpp stays thin.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "simpartner/teleop/teleop.h"

struct _SDL_GameController;
struct _SDL_Joystick;
union SDL_Event;

namespace simpartner::teleop {

// The first game controller SDL knows; a controller plugged in later is
// opened then, an unplugged one closed (input: not connected).
class Gamepad {
 public:
  explicit Gamepad(std::ostream& log) : log_(log) {}
  ~Gamepad();
  Gamepad(const Gamepad&) = delete;
  Gamepad& operator=(const Gamepad&) = delete;
  // Opens the first controller if none is open (at start).
  void OpenFirst();
  // Hot-plug events (SDL_CONTROLLERDEVICEADDED / REMOVED).
  void Handle(const SDL_Event& event);
  InputState Read() const;
  std::string name() const;

 private:
  std::ostream& log_;
  _SDL_GameController* controller_ = nullptr;
  int instance_id_ = -1;
};

// "0: Xbox 360 Controller" per connected game controller.
std::vector<std::string> ListControllers();

// The keyboard stands in for a controller: arrows or WASD are the left
// stick, space is the dead-man (held), R/F the first level's +/- buttons,
// Q/E the second's, C/O the third's; the window's title shows the status.
InputState KeyboardInput(const Plan* plan);

// A virtual game controller (SDL_JoystickAttachVirtualEx) the test build
// drives from a script, one command a line:
//   axis <name> <-1..1> | button <name> <0|1> | detach | attach | quit
class VirtualPad {
 public:
  explicit VirtualPad(std::ostream& log) : log_(log) {}
  ~VirtualPad();
  void Attach();
  void Detach();
  // Applies one script line; returns false on "quit". Throws
  // std::runtime_error for a bad line (naming it).
  bool Apply(const std::string& line);

 private:
  std::ostream& log_;
  int device_index_ = -1;
  _SDL_Joystick* joystick_ = nullptr;
};

// The whole program: args without the program name. `virtual_pad`: the
// test build (simpartner-teleop-vpad) that reads a VirtualPad script on
// stdin. Returns the exit status.
int RunTeleop(const std::vector<std::string>& args, bool virtual_pad, std::ostream& out,
              std::ostream& err);

}  // namespace simpartner::teleop
