// Teleop's keyboard window: the window that takes the key presses shows,
// in it, what teleop is doing (the status line, coloured by why the robot
// stands or that it moves) and the keys. The title bar alone is not
// enough: without a window manager (Xvfb, a kiosk) there is none.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/teleop/mapping.h"
#include "simpartner/teleop/teleop.h"

struct SDL_Window;
struct SDL_Renderer;

namespace simpartner::teleop {

// The keys of the keyboard stand-in for `plan` (or the fixed ones before a
// plan), one per line: "hold SPACE: dead-man (drives only while held)".
std::vector<std::string> KeyboardHelpLines(const Plan* plan);

// The status line split into lines of at most `columns` characters at its
// " | " separators (a part longer than a line is cut).
std::vector<std::string> WrapStatus(const std::string& status, size_t columns);

class KeyboardWindow {
 public:
  // Opens the window; throws std::runtime_error with SDL's reason.
  KeyboardWindow();
  ~KeyboardWindow();
  KeyboardWindow(const KeyboardWindow&) = delete;
  KeyboardWindow& operator=(const KeyboardWindow&) = delete;

  // Draws the status (on a background green while moving, amber when the
  // dead-man stops it, red for any other stop) and the help lines when
  // any of them changed, and twice a second (a window uncovered again);
  // software drawing at teleop's 100 Hz would take a core.
  void Update(const std::string& status, StopReason stop, const std::vector<std::string>& help);

  static constexpr int kWidth = 720;
  static constexpr int kHeight = 270;
  static constexpr int kRowPitch = 10;  // glyph rows + 3 between lines
  static constexpr int kScale = 2;  // font pixels per glyph pixel
  static constexpr size_t kColumns = kWidth / (kScale * 6) - 2;

 private:
  void Draw(const std::string& status, StopReason stop, const std::vector<std::string>& help);
  void DrawText(const std::string& text, int column, int row);

  SDL_Window* window_ = nullptr;
  SDL_Renderer* renderer_ = nullptr;
  std::string drawn_status_;
  StopReason drawn_stop_ = StopReason::kNone;
  std::vector<std::string> drawn_help_;
  std::chrono::steady_clock::time_point drawn_at_{};
};

}  // namespace simpartner::teleop
