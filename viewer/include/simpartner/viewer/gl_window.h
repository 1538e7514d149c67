// SDL and a window with an OpenGL 2.1 compatibility context (the
// fixed-function calls the renderer uses), released in reverse order. The
// viewer shows it; simpartner-camera keeps it hidden and draws into
// framebuffer objects, needing the window only for the context.
#pragma once

#include <SDL2/SDL.h>

#include <string>
#include <utility>

namespace simpartner::viewer {

class GlWindow {
 public:
  // Throws std::runtime_error saying what SDL or the driver refused.
  GlWindow(const std::string& title, int width, int height, bool vsync, bool hidden = false);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;

  SDL_Window* get() const { return window_; }
  std::pair<int, int> DrawableSize() const;

 private:
  bool sdl_started_ = false;
  SDL_Window* window_ = nullptr;
  SDL_GLContext context_ = nullptr;
};

}  // namespace simpartner::viewer
