// A private X server (Xvfb) for headless rendering: tests, benchmarks and
// documentation screenshots start one with a free display number (Xvfb
// picks it and reports it through -displayfd) and stop it by its own PID.
#pragma once

#include <memory>
#include <string>

#include "simpartner/child_process.h"

namespace simpartner::viewer {

class XvfbServer {
 public:
  // Starts `Xvfb -displayfd FD -nolisten tcp -screen 0 WxHx24` and waits
  // (up to 10 s) until it names its display. Throws std::runtime_error
  // with Xvfb's log when it does not start.
  XvfbServer(int width, int height, const std::string& log_path);
  ~XvfbServer();  // SIGTERM, then SIGKILL after 2 s
  XvfbServer(const XvfbServer&) = delete;
  XvfbServer& operator=(const XvfbServer&) = delete;

  const std::string& display() const { return display_; }  // ":N"
  pid_t pid() const { return child_->pid(); }

 private:
  std::unique_ptr<ChildProcess> child_;
  std::string display_;
};

}  // namespace simpartner::viewer
