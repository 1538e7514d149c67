#include "simpartner/viewer/xvfb.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace simpartner::viewer {
namespace {

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

XvfbServer::XvfbServer(int width, int height, const std::string& log_path) {
  // Xvfb writes the display number it chose to this pipe. The write end is
  // inherited by Xvfb (it is not close-on-exec) and closed here at once.
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("Xvfb: cannot make a pipe");
  ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);
  const std::string screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
  try {
    child_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{"/usr/bin/Xvfb", "-displayfd", std::to_string(fds[1]),
                                 "-nolisten", "tcp", "-screen", "0", screen},
        log_path);
  } catch (...) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw;
  }
  ::close(fds[1]);
  std::string number;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    pollfd p{fds[0], POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) {
      if (!child_->running()) break;
      continue;
    }
    char c = 0;
    if (::read(fds[0], &c, 1) != 1) break;  // EOF: Xvfb ended
    if (c == '\n') break;
    number += c;
  }
  ::close(fds[0]);
  if (number.empty())
    throw std::runtime_error("Xvfb did not start (screen " + screen + "); its log " + log_path +
                             ":\n" + ReadFile(log_path));
  display_ = ":" + number;
}

XvfbServer::~XvfbServer() {
  if (!child_) return;
  child_->Signal(SIGTERM);
  if (!child_->Wait(std::chrono::seconds(2))) child_->Signal(SIGKILL);
  child_->Wait(std::chrono::seconds(2));
}

}  // namespace simpartner::viewer
