#include "simpartner/viewer/gl_window.h"

#include <algorithm>
#include <stdexcept>

namespace simpartner::viewer {

GlWindow::GlWindow(const std::string& title, int width, int height, bool vsync, bool hidden) {
  if (SDL_Init(SDL_INIT_VIDEO) != 0)
    throw std::runtime_error(std::string("SDL cannot start video (is DISPLAY set?): ") +
                             SDL_GetError());
  sdl_started_ = true;
  // GL 2.1 compatibility: the fixed-function calls the renderer uses.
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 2);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24);
  SDL_GL_SetAttribute(SDL_GL_STENCIL_SIZE, 8);  // the ruts' openings (renderer.cpp)
  const Uint32 flags = SDL_WINDOW_OPENGL | static_cast<Uint32>(hidden ? SDL_WINDOW_HIDDEN
                                                                     : SDL_WINDOW_RESIZABLE);
  window_ = SDL_CreateWindow(title.c_str(), SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, width,
                             height, flags);
  if (window_ == nullptr)
    throw std::runtime_error(std::string("SDL cannot open a ") + std::to_string(width) + "x" +
                             std::to_string(height) + " OpenGL window: " + SDL_GetError());
  context_ = SDL_GL_CreateContext(window_);
  if (context_ == nullptr)
    throw std::runtime_error(std::string("no OpenGL 2.1 context: ") + SDL_GetError());
  // Vsync where the driver has it; the frame cap covers the rest.
  SDL_GL_SetSwapInterval(vsync ? 1 : 0);
}

GlWindow::~GlWindow() {
  if (context_ != nullptr) SDL_GL_DeleteContext(context_);
  if (window_ != nullptr) SDL_DestroyWindow(window_);
  if (sdl_started_) SDL_Quit();
}

std::pair<int, int> GlWindow::DrawableSize() const {
  int w = 0, h = 0;
  SDL_GL_GetDrawableSize(window_, &w, &h);
  return {std::max(w, 1), std::max(h, 1)};
}

}  // namespace simpartner::viewer
