// Reading a file a user names (a model, parameters, a mapping, a database
// option file, a sequence, a batch): the one way every program does it.
//
// Regular files only (and /dev/null, read as empty): a FIFO, device, socket or directory is refused by
// its type before any read, so /dev/zero is not read without end and a
// FIFO without a writer never blocks (it is opened O_NONBLOCK). At most
// `max_bytes`, also for a file that grows while it is read. A process
// reading a file therefore never waits on it, and stops on SIGTERM as
// before.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace simpartner {

// Settings files: parameters, teleop mappings, database option files. The
// largest shipped one is ~6 KB.
inline constexpr size_t kMaxSettingsFileBytes = 1024 * 1024;

class FileReadError : public std::runtime_error {
 public:
  // reason: without the path ("not a regular file (FIFO); ...").
  FileReadError(std::string path, const std::string& reason, bool cannot_open)
      : std::runtime_error(reason), path_(std::move(path)), cannot_open_(cannot_open) {}
  const std::string& path() const { return path_; }
  // The file could not be opened or read (missing, no permission, an I/O
  // error), as opposed to refused (type, size).
  bool cannot_open() const { return cannot_open_; }

 private:
  std::string path_;
  bool cannot_open_;
};

// The whole file. `kind` names such files in a refusal, in the plural:
// "model files" gives "not a regular file (FIFO); model files must be
// regular files" and "file is 70000000 bytes (66.76 MiB); model files may
// have at most 67108864 bytes (64 MiB)". Throws FileReadError.
std::string ReadBoundedFile(const std::string& path, size_t max_bytes, const std::string& kind);

}  // namespace simpartner
