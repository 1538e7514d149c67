// Reading a model file's bytes: regular files only, never more than
// kMaxModelFileBytes, and the reason when it cannot be read.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "parts.h"
#include "simpartner/text.h"

namespace simpartner::model {
namespace {

const char* FileTypeName(mode_t mode) {
  if (S_ISDIR(mode)) return "directory";
  if (S_ISCHR(mode)) return "character device";
  if (S_ISBLK(mode)) return "block device";
  if (S_ISFIFO(mode)) return "FIFO";
  if (S_ISSOCK(mode)) return "socket";
  return "special file";
}

// Closes a file descriptor on every path out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

std::string SizeText(long long bytes) {
  return std::to_string(bytes) + " bytes (" + FormatNumber(static_cast<double>(bytes) / 1048576.0, 10) +
         " MiB)";
}

}  // namespace

namespace detail {

// Reads a model file through reader; on failure adds a diagnostic at the
// file (the reader's reason when it gave one) and returns false.
bool ReadModelFile(const std::string& path, const FileReader& read, const char* kind,
                   std::string* xml, DiagnosticList* diagnostics) {
  try {
    if (read(path, xml)) return true;
    diagnostics->Add(path, 0, "", std::string("cannot read ") + kind + " file");
  } catch (const ModelFileError& e) {
    diagnostics->Add(path, 0, "",
                     e.cannot_open() ? std::string("cannot read ") + kind + " file: " + e.what()
                                     : std::string(e.what()));
  }
  return false;
}

}  // namespace detail

bool ReadFileFromDisk(const std::string& path, std::string* contents) {
  // O_NONBLOCK: opening a FIFO without a writer must not wait for one; the
  // type check below refuses it before any read.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) throw ModelFileError(std::strerror(errno), true);
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0)
    throw ModelFileError(std::string("cannot stat: ") + std::strerror(errno), true);
  if (!S_ISREG(info.st_mode))
    throw ModelFileError(std::string("not a regular file (") + FileTypeName(info.st_mode) +
                         "); model files must be regular files",
                         false);
  if (info.st_size > kMaxModelFileBytes)
    throw ModelFileError("file is " + SizeText(info.st_size) + "; model files may have at most " +
                         SizeText(kMaxModelFileBytes),
                         false);
  // Read up to one byte past the limit: a file that grows while it is read
  // is refused too, never read without end.
  contents->clear();
  contents->reserve(static_cast<size_t>(info.st_size));
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw ModelFileError(std::strerror(errno), true);
    }
    if (n == 0) break;
    contents->append(buffer, static_cast<size_t>(n));
    if (static_cast<long long>(contents->size()) > kMaxModelFileBytes)
      throw ModelFileError("file grew beyond " + SizeText(kMaxModelFileBytes) +
                           " while it was read; model files may have at most that",
                           false);
  }
  return true;
}

}  // namespace simpartner::model
