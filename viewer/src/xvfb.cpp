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

XvfbServer::XvfbServer(int width, int height, const std::string& log_path,
                       const std::string& framebuffer_dir) {
  // Xvfb writes the display number it chose to this pipe. The write end is
  // inherited by Xvfb (it is not close-on-exec) and closed here at once.
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("Xvfb: cannot make a pipe");
  ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);
  const std::string screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
  std::vector<std::string> argv = {"/usr/bin/Xvfb", "-displayfd", std::to_string(fds[1]),
                                   "-nolisten", "tcp", "-screen", "0", screen};
  if (!framebuffer_dir.empty()) {
    argv.insert(argv.end(), {"-fbdir", framebuffer_dir});
    framebuffer_file_ = framebuffer_dir + "/Xvfb_screen0";
  }
  try {
    child_ = std::make_unique<ChildProcess>(argv, log_path);
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

ScreenImage XvfbServer::ReadScreen() const {
  if (framebuffer_file_.empty())
    throw std::runtime_error("Xvfb " + display_ + " was started without a framebuffer directory");
  const std::string data = ReadFile(framebuffer_file_);
  // XWDFileHeader: 25 big-endian 32-bit fields, then the colour map
  // (12 bytes an entry), then the image.
  auto field = [&](int i) {
    const auto* b = reinterpret_cast<const unsigned char*>(data.data()) + 4 * i;
    return static_cast<uint32_t>(b[0]) << 24 | static_cast<uint32_t>(b[1]) << 16 |
           static_cast<uint32_t>(b[2]) << 8 | b[3];
  };
  const auto fail = [&](const std::string& why) {
    return std::runtime_error("Xvfb screen file " + framebuffer_file_ + ": " + why);
  };
  if (data.size() < 100) throw fail("shorter than an XWD header");
  const uint32_t header_size = field(0), format = field(2), width = field(4), height = field(5),
                 byte_order = field(7), bits_per_pixel = field(11), bytes_per_line = field(12),
                 colours = field(19);
  if (format != 2 || bits_per_pixel != 32 || byte_order != 0)
    throw fail("not a 32-bit little-endian ZPixmap (format " + std::to_string(format) + ", " +
               std::to_string(bits_per_pixel) + " bits per pixel, byte order " +
               std::to_string(byte_order) + ")");
  const size_t image = static_cast<size_t>(header_size) + 12u * colours;
  if (bytes_per_line < 4 * width || data.size() < image + static_cast<size_t>(bytes_per_line) * height)
    throw fail("shorter than its " + std::to_string(width) + "x" + std::to_string(height) + " image");
  ScreenImage screen;
  screen.width = static_cast<int>(width);
  screen.height = static_cast<int>(height);
  screen.pixels.reserve(static_cast<size_t>(width) * height);
  for (uint32_t y = 0; y < height; ++y) {
    const auto* row = reinterpret_cast<const unsigned char*>(data.data()) + image +
                      static_cast<size_t>(y) * bytes_per_line;
    for (uint32_t x = 0; x < width; ++x) {
      const unsigned char* p = row + 4 * x;  // B G R X
      screen.pixels.push_back(static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[1]) << 8 | p[0]);
    }
  }
  return screen;
}

XvfbServer::~XvfbServer() {
  if (!child_) return;
  child_->Signal(SIGTERM);
  if (!child_->Wait(std::chrono::seconds(2))) child_->Signal(SIGKILL);
  child_->Wait(std::chrono::seconds(2));
}

}  // namespace simpartner::viewer
