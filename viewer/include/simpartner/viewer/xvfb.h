// A private X server (Xvfb) for headless rendering: tests, benchmarks and
// documentation screenshots start one with a free display number (Xvfb
// picks it and reports it through -displayfd) and stop it by its own PID.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/child_process.h"

namespace simpartner::viewer {

// The screen as Xvfb holds it: what a screenshot of the display shows.
struct ScreenImage {
  int width = 0;
  int height = 0;
  std::vector<uint32_t> pixels;  // 0xRRGGBB, row by row from the top
  uint32_t At(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

class XvfbServer {
 public:
  // Starts `Xvfb -displayfd FD -nolisten tcp -screen 0 WxHx24` and waits
  // (up to 10 s) until it names its display. Throws std::runtime_error
  // with Xvfb's log when it does not start. With a `framebuffer_dir`
  // (-fbdir), Xvfb keeps its screen in a file there, which ReadScreen()
  // reads: a screenshot of any window, with no X client to take it.
  XvfbServer(int width, int height, const std::string& log_path,
             const std::string& framebuffer_dir = "");
  ~XvfbServer();  // SIGTERM, then SIGKILL after 2 s
  XvfbServer(const XvfbServer&) = delete;
  XvfbServer& operator=(const XvfbServer&) = delete;

  const std::string& display() const { return display_; }  // ":N"
  pid_t pid() const { return child_->pid(); }
  // The screen now (XWD, 24-bit ZPixmap). Throws std::runtime_error
  // naming the file when there is no framebuffer_dir or it cannot be read.
  ScreenImage ReadScreen() const;

 private:
  std::unique_ptr<ChildProcess> child_;
  std::string display_;
  std::string framebuffer_file_;
};

}  // namespace simpartner::viewer
