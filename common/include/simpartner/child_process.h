// A child process started by tests, benchmarks and launch scripts: argv
// as given (no shell), stdout and stderr to a log file, never left behind
// (the destructor kills and reaps it).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace simpartner {

class ChildProcess {
 public:
  // Starts argv[0] with argv; output goes to log_path ("/dev/null" to drop
  // it). Throws std::runtime_error naming the program if it cannot start.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path);
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  // Exit status (128 + signal when killed) once it has ended; std::nullopt
  // if it is still running after `timeout`.
  std::optional<int> Wait(std::chrono::milliseconds timeout);
  bool running();
  // Sends `signal` (SIGTERM, SIGKILL, SIGSTOP ...) unless it has ended.
  void Signal(int signal);

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

}  // namespace simpartner
