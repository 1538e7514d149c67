#include "simpartner/viewer/keys.h"

namespace simpartner::viewer {
namespace {

struct Binding {
  SDL_Keycode key;
  KeyAction action;
};

constexpr Binding kBindings[] = {
    {SDLK_ESCAPE, KeyAction::kQuit},
    {SDLK_F1, KeyAction::kToggleHelp},
    {SDLK_h, KeyAction::kToggleHelp},
    {SDLK_SPACE, KeyAction::kTogglePause},
    {SDLK_n, KeyAction::kStep},
    {SDLK_m, KeyAction::kStep100},
    {SDLK_r, KeyAction::kReset},
    {SDLK_w, KeyAction::kToggleWireframe},
    {SDLK_b, KeyAction::kToggleFrames},
    {SDLK_c, KeyAction::kToggleContactForces},
    {SDLK_j, KeyAction::kToggleJointForces},
    {SDLK_s, KeyAction::kToggleScannerRays},
    {SDLK_g, KeyAction::kToggleGrid},
    {SDLK_u, KeyAction::kToggleHud},
    {SDLK_f, KeyAction::kToggleFollow},
    {SDLK_HOME, KeyAction::kResetCamera},
    {SDLK_p, KeyAction::kScreenshot},
    {SDLK_i, KeyAction::kNextCameraImage},
    {SDLK_UP, KeyAction::kFlyForward},
    {SDLK_DOWN, KeyAction::kFlyBack},
    {SDLK_LEFT, KeyAction::kFlyLeft},
    {SDLK_RIGHT, KeyAction::kFlyRight},
    {SDLK_PAGEUP, KeyAction::kFlyUp},
    {SDLK_PAGEDOWN, KeyAction::kFlyDown},
};

}  // namespace

KeyAction ActionForKey(SDL_Keycode key) {
  for (const Binding& b : kBindings)
    if (b.key == key) return b.action;
  return KeyAction::kNone;
}

bool IsFlyAction(KeyAction a) {
  switch (a) {
    case KeyAction::kFlyForward:
    case KeyAction::kFlyBack:
    case KeyAction::kFlyLeft:
    case KeyAction::kFlyRight:
    case KeyAction::kFlyUp:
    case KeyAction::kFlyDown: return true;
    default: return false;
  }
}

std::vector<std::string> KeyHelpLines() {
  return {
      "mouse left drag     orbit the camera",
      "mouse right drag    pan (also middle drag, or shift + left drag)",
      "mouse wheel         zoom",
      "arrow keys          fly forward/back/left/right (shift: faster)",
      "PageUp / PageDown   fly up / down",
      "f                   follow the robot on/off (flying turns it off)",
      "Home                camera back to the start view",
      "space               pause / resume the sim (SIM_CONTROL)",
      "n / m               step the sim 1 / 100 steps (pauses it)",
      "r                   reset the sim to step 0",
      "w                   wireframe on/off",
      "b                   body frames on/off",
      "c                   contact forces on/off",
      "j                   joint forces on/off",
      "s                   scanner rays on/off",
      "g                   ground grid on/off",
      "u                   HUD line on/off",
      "p                   save a screenshot (viewer-<time>.png)",
      "i                   next camera's image in the corner, then none (simpartner-camera)",
      "h or F1             this list",
      "Esc                 quit the viewer (the sim runs on)",
  };
}

}  // namespace simpartner::viewer
