#include "simpartner/teleop/keyboard_window.h"

#include <SDL2/SDL.h>

#include <stdexcept>

#include "simpartner/bitmap_font.h"

namespace simpartner::teleop {
namespace {

// The keys KeyboardInput reads for the plan's first three levels.
constexpr const char* kLevelKeys[3] = {"R / F", "Q / E", "O / C"};

}  // namespace

std::vector<std::string> KeyboardHelpLines(const Plan* plan) {
  std::vector<std::string> lines = {"hold SPACE: dead-man (drives only while held)",
                                    "arrows or WASD: drive forward/back, steer left/right"};
  if (plan != nullptr)
    for (size_t k = 0; k < plan->levels.size() && k < 3; ++k)
      lines.push_back(std::string(kLevelKeys[k]) + ": " + plan->levels[k].name + " up / down");
  lines.push_back("Esc or close the window: stop the wheels and quit");
  return lines;
}

std::vector<std::string> WrapStatus(const std::string& status, size_t columns) {
  std::vector<std::string> lines;
  std::string line;
  size_t begin = 0;
  while (begin <= status.size()) {
    size_t end = status.find(" | ", begin);
    if (end == std::string::npos) end = status.size();
    std::string part = status.substr(begin, end - begin).substr(0, columns);
    if (!line.empty() && line.size() + 3 + part.size() > columns) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " | ") + part;
    begin = end + 3;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

KeyboardWindow::KeyboardWindow() {
  window_ = SDL_CreateWindow("simpartner-teleop", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED,
                             kWidth, kHeight, SDL_WINDOW_SHOWN);
  if (window_ == nullptr)
    throw std::runtime_error(std::string("cannot open the keyboard window: ") + SDL_GetError());
  renderer_ = SDL_CreateRenderer(window_, -1, SDL_RENDERER_SOFTWARE);
  if (renderer_ == nullptr) {
    const std::string why = SDL_GetError();
    SDL_DestroyWindow(window_);
    throw std::runtime_error("cannot draw in the keyboard window: " + why);
  }
  SDL_RenderSetScale(renderer_, kScale, kScale);
}

KeyboardWindow::~KeyboardWindow() {
  SDL_DestroyRenderer(renderer_);
  SDL_DestroyWindow(window_);
}

void KeyboardWindow::DrawText(const std::string& text, int column, int row) {
  SDL_SetRenderDrawColor(renderer_, 255, 255, 255, 255);
  for (size_t i = 0; i < text.size(); ++i) {
    const auto rows = Glyph(text[i]);
    const int x0 = (column + static_cast<int>(i)) * kCellWidth;
    const int y0 = row * kRowPitch;
    for (int y = 0; y < kGlyphHeight; ++y)
      for (int x = 0; x < kGlyphWidth; ++x)
        if (rows[static_cast<size_t>(y)] & (0x10 >> x)) SDL_RenderDrawPoint(renderer_, x0 + x, y0 + y);
  }
}

void KeyboardWindow::Update(const std::string& status, StopReason stop,
                            const std::vector<std::string>& help) {
  const auto now = std::chrono::steady_clock::now();
  if (status == drawn_status_ && stop == drawn_stop_ && help == drawn_help_ &&
      now - drawn_at_ < std::chrono::milliseconds(500))
    return;
  Draw(status, stop, help);
  drawn_status_ = status;
  drawn_stop_ = stop;
  drawn_help_ = help;
  drawn_at_ = now;
}

void KeyboardWindow::Draw(const std::string& status, StopReason stop,
                          const std::vector<std::string>& help) {
  // Green while moving, amber when stopped by the dead-man, red else.
  if (stop == StopReason::kNone) SDL_SetRenderDrawColor(renderer_, 40, 130, 60, 255);
  else if (stop == StopReason::kDeadman) SDL_SetRenderDrawColor(renderer_, 170, 120, 20, 255);
  else SDL_SetRenderDrawColor(renderer_, 150, 40, 40, 255);
  SDL_RenderClear(renderer_);
  int row = 1;
  for (const std::string& line : WrapStatus(status, kColumns)) DrawText(line, 1, row++);
  ++row;
  for (const std::string& line : help) DrawText(line.substr(0, kColumns), 1, row++);
  SDL_RenderPresent(renderer_);
}

}  // namespace simpartner::teleop
