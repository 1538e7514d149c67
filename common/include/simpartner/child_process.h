// A child process started by tests, benchmarks, the batch and launch
// scripts: argv as given (no shell), stdout and stderr to a log file,
// never left behind (the destructor kills and reaps it).
#pragma once

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace simpartner {

struct ChildOptions {
  // In a process group of its own (its pid): Signal and the destructor
  // reach what it started too, unless that left the group (a controller's
  // helpers, a shell's commands).
  bool own_group = false;
  // SIGTERM to it when the thread that started it ends, the whole parent
  // process with it, even by kill -9 (prctl PR_SET_PDEATHSIG): nothing
  // runs on unsupervised.
  bool stop_with_parent = false;
  // In a session of its own (setsid), as scripts/run starts the programs:
  // its own scheduling group (sched_autogroup), not one shared with the
  // parent and whatever else the parent's session runs. Implies a group
  // of its own, but Signal reaches only the program unless own_group.
  bool own_session = false;
};

class ChildProcess {
 public:
  // Starts argv[0] with argv; output goes to log_path ("/dev/null" to drop
  // it). Throws std::runtime_error naming the program if it cannot start.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path,
               ChildOptions options = {});
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess();

  pid_t pid() const { return pid_; }
  // Exit status (128 + signal when killed) once it has ended; std::nullopt
  // if it is still running after `timeout`.
  std::optional<int> Wait(std::chrono::milliseconds timeout);
  bool running();
  // Sends `signal` (SIGTERM, SIGKILL, SIGSTOP ...) unless it has ended;
  // with own_group, to its whole group, also after it ended (what it
  // started may still run).
  void Signal(int signal);

 private:
  pid_t pid_ = -1;
  bool own_group_ = false;
  std::optional<int> status_;
};

}  // namespace simpartner
