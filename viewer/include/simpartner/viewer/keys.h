// Keyboard and mouse bindings of the viewer, apart from the window so that
// the mapping and the on-screen list are tested without a display.
#pragma once

#include <SDL2/SDL_keycode.h>

#include <string>
#include <vector>

namespace simpartner::viewer {

enum class KeyAction {
  kNone,
  kQuit,
  kToggleHelp,
  kTogglePause,    // SIM_CONTROL pause or resume, by the last SIM_STATUS
  kStep,           // SIM_CONTROL step 1
  kStep100,        // SIM_CONTROL step 100
  kReset,          // SIM_CONTROL reset
  kToggleWireframe,
  kToggleFrames,
  kToggleContactForces,
  kToggleJointForces,
  kToggleScannerRays,
  kToggleGrid,
  kToggleHud,
  kToggleFollow,
  kResetCamera,
  kScreenshot,     // viewer-<time>.png in the working directory
  kNextCameraImage,  // the inset shows the next camera's image (SIM_IMAGE), then none
  // Free flight (held keys); shift flies faster.
  kFlyForward,
  kFlyBack,
  kFlyLeft,
  kFlyRight,
  kFlyUp,
  kFlyDown,
};

KeyAction ActionForKey(SDL_Keycode key);
bool IsFlyAction(KeyAction action);

// "key  what it does" lines for --help and the on-screen list (F1 or h).
std::vector<std::string> KeyHelpLines();

}  // namespace simpartner::viewer
