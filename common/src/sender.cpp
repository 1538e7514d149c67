#include "simpartner/sender.h"

#include <unistd.h>

#include <chrono>

namespace simpartner {

std::string HostName() {
  char name[256] = {0};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

std::string SenderName(const std::string& program) {
  return program + "@" + HostName() + ":" + std::to_string(::getpid());
}

int64_t WallMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace simpartner
