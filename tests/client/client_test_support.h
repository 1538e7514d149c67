// Real simpartner-sim processes for the client tests: each on a udpm port
// of its own (ttl=0), killed and reaped when the test ends.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/child_process.h"

namespace simpartner::client::testing {

// A port per test process and per call, so that ctest -j does not mix them.
inline std::string UniqueUrl(int offset) {
  const int port = 20000 + (static_cast<int>(::getpid()) * 13 + offset * 101) % 20000;
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
}

// The number printed right after `label` in `text` (GCC 12 warns falsely
// inside <regex> under the sanitizers, so no std::regex here).
inline std::optional<double> NumberAfter(const std::string& text, const std::string& label) {
  const size_t at = text.find(label);
  if (at == std::string::npos) return std::nullopt;
  const char* start = text.c_str() + at + label.size();
  char* end = nullptr;
  const double value = std::strtod(start, &end);
  if (end == start) return std::nullopt;
  return value;
}

inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::filesystem::path TestDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("sp_client_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::create_directories(dir);
  return dir;
}

// simpartner-sim of this build on `world` (models/worlds/...), with extra
// parameters such as "--speed=0".
class SimProcess {
 public:
  SimProcess(const std::string& world, const std::string& url, const std::string& log,
             std::vector<std::string> extra = {})
      : log_(log), child_(Args(world, url, std::move(extra)), log) {}
  ChildProcess& child() { return child_; }
  std::string Log() const { return ReadFile(log_); }

 private:
  static std::vector<std::string> Args(const std::string& world, const std::string& url,
                                       std::vector<std::string> extra) {
    std::vector<std::string> args = {std::string(SP_BINARY_DIR) + "/sim_core/simpartner-sim",
                                     "--params", "/dev/null",
                                     "--environment=" + std::string(SP_SOURCE_DIR) +
                                         "/models/worlds/" + world,
                                     "--lcm-url", url};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }
  std::string log_;
  ChildProcess child_;
};

}  // namespace simpartner::client::testing
