#include "simpartner/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace simpartner {
namespace {

// In the child, between fork and exec: only async-signal-safe calls. On
// failure its errno goes up `report` (close-on-exec: nothing comes when
// the exec succeeds).
[[noreturn]] void BecomeChild(char* const* argv, const char* log_path, ChildOptions options,
                              pid_t parent, int report) {
  int error = 0;
  if (options.own_session && ::setsid() < 0) error = errno;
  if (error == 0 && options.own_group && !options.own_session && ::setpgid(0, 0) != 0) error = errno;
  if (error == 0 && options.stop_with_parent) {
    if (::prctl(PR_SET_PDEATHSIG, SIGTERM) != 0) error = errno;
    // The parent may have died before the prctl: then nobody sends it.
    else if (::getppid() != parent) ::_exit(127);
  }
  if (error == 0) {
    const int log = ::open(log_path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0 || ::dup2(log, 1) < 0 || ::dup2(log, 2) < 0) error = errno;
  }
  if (error == 0) {
    ::execve(argv[0], argv, environ);
    error = errno;
  }
  while (::write(report, &error, sizeof error) < 0 && errno == EINTR) {
  }
  ::_exit(127);
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& log_path,
                           ChildOptions options)
    : own_group_(options.own_group) {
  if (argv.empty()) throw std::runtime_error("ChildProcess: empty argv");
  std::vector<std::string> copy = argv;
  std::vector<char*> cargs;
  for (std::string& a : copy) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0)
    throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(errno));
  const pid_t parent = ::getpid();
  pid_ = ::fork();
  if (pid_ == 0) BecomeChild(cargs.data(), log_path.c_str(), options, parent, report[1]);
  const int fork_error = errno;
  ::close(report[1]);
  int error = pid_ < 0 ? fork_error : 0;
  if (pid_ > 0) {
    ssize_t got;
    while ((got = ::read(report[0], &error, sizeof error)) < 0 && errno == EINTR) {
    }
    if (got != static_cast<ssize_t>(sizeof error)) error = 0;  // it exec'd
  }
  ::close(report[0]);
  if (error != 0) {
    if (pid_ > 0) ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
    throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(error));
  }
  // The group exists before the caller signals it (the child's own setpgid
  // may not have run yet).
  if (own_group_ && !options.own_session) ::setpgid(pid_, pid_);
}

ChildProcess::~ChildProcess() {
  if (pid_ <= 0) return;
  if (own_group_) ::kill(-pid_, SIGKILL);
  if (!status_) {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
  }
}

std::optional<int> ChildProcess::Wait(std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!status_) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) {
      status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      break;
    }
    if (std::chrono::steady_clock::now() >= end) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return status_;
}

bool ChildProcess::running() { return !Wait(std::chrono::milliseconds(0)); }

void ChildProcess::Signal(int signal) {
  if (own_group_) {
    ::kill(-pid_, signal);
    return;
  }
  if (running()) ::kill(pid_, signal);
}

}  // namespace simpartner
