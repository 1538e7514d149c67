#include "mariadb_seed.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <vector>

#include "processes.h"
#include "programs.h"
#include "text_file.h"

namespace simpartner::test_support {
namespace {

namespace fs = std::filesystem;

// Runs argv to its end (test_support::RunToEnd); throws with its output
// when it fails.
void RunOrThrow(const std::vector<std::string>& argv, const fs::path& log) {
  const ProgramRun run = RunToEnd(argv, log.string(), std::chrono::seconds(120));
  if (run.status == 0) return;
  std::string command;
  for (const std::string& a : argv) command += (command.empty() ? "" : " ") + a;
  throw std::runtime_error("MariaDbSeed: '" + command + "' failed (" +
                           (run.status < 0 ? std::string("still running after 120 s")
                                           : "exit " + std::to_string(run.status)) +
                           "): " + run.output);
}

// Holds an exclusive lock on a file while it lives.
class FileLock {
 public:
  explicit FileLock(const fs::path& path) : fd_(::open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0)
      throw std::runtime_error("MariaDbSeed: cannot lock " + path.string());
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock() {
    if (fd_ >= 0) ::close(fd_);
  }

 private:
  int fd_;
};

}  // namespace

std::string MariaDbSeed() {
  const std::string script = SourceDir() + "/scripts/mariadb";
  const fs::path seed = fs::path(BinaryDir()) / "tests" / "mariadb-seed";
  // What the seed was made by: another script may make another server.
  const std::string maker = std::to_string(std::hash<std::string>{}(ReadText(script)));
  FileLock lock(seed.string() + ".lock");
  if (fs::exists(seed / "data" / "mysql") && ReadText(seed / "made-by") == maker) return seed.string();
  fs::remove_all(seed);
  // Made under a short temporary path (the socket's must fit in 108 bytes),
  // then copied beside the build's other files.
  const fs::path made = fs::temp_directory_path() / ("sp_seed_" + std::to_string(::getpid()));
  fs::remove_all(made);
  fs::create_directories(made);
  fs::create_directories(seed);
  const std::vector<std::string> stop = {"/bin/bash", script, "stop", "--datadir", made.string()};
  try {
    RunOrThrow({"/bin/bash", script, "start", "--datadir", made.string()}, seed / "start.log");
  } catch (const std::runtime_error&) {
    // A server may run though its start failed later (users, grants).
    RunToEnd(stop, (seed / "stop.log").string(), std::chrono::seconds(120));
    throw;
  }
  RunOrThrow(stop, seed / "stop.log");
  RunOrThrow({"/bin/cp", "-a", "--sparse=always", (made / "data").string(), (seed / "data").string()},
           seed / "copy.log");
  fs::remove_all(made);
  std::ofstream(seed / "made-by") << maker;
  return seed.string();
}

}  // namespace simpartner::test_support
