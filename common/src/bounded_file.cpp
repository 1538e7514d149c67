#include "simpartner/bounded_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "simpartner/text.h"

namespace simpartner {
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

bool IsDevNull(const struct stat& info) {
  struct stat null_info {};
  return ::stat("/dev/null", &null_info) == 0 && S_ISCHR(null_info.st_mode) &&
         info.st_rdev == null_info.st_rdev;
}

std::string SizeText(unsigned long long bytes) {
  return std::to_string(bytes) + " bytes (" +
         FormatNumber(static_cast<double>(bytes) / 1048576.0, 10) + " MiB)";
}

}  // namespace

std::string ReadBoundedFile(const std::string& path, size_t max_bytes, const std::string& kind) {
  // O_NONBLOCK: opening a FIFO without a writer must not wait for one; the
  // type check below refuses it before any read.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) throw FileReadError(path, std::strerror(errno), true);
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0)
    throw FileReadError(path, std::string("cannot stat: ") + std::strerror(errno), true);
  // /dev/null is the usual way to say "an empty file" (--params /dev/null).
  if (S_ISCHR(info.st_mode) && IsDevNull(info)) return "";
  if (!S_ISREG(info.st_mode))
    throw FileReadError(path,
                        std::string("not a regular file (") + FileTypeName(info.st_mode) + "); " +
                            kind + " must be regular files",
                        false);
  if (static_cast<unsigned long long>(info.st_size) > max_bytes)
    throw FileReadError(path,
                        "file is " + SizeText(static_cast<unsigned long long>(info.st_size)) +
                            "; " + kind + " may have at most " + SizeText(max_bytes),
                        false);
  // Read up to one buffer past the limit: a file that grows while it is
  // read is refused too, never read without end.
  std::string contents;
  contents.reserve(static_cast<size_t>(info.st_size));
  char buffer[65536];
  for (;;) {
    const ssize_t n = ::read(fd.get(), buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw FileReadError(path, std::strerror(errno), true);
    }
    if (n == 0) break;
    contents.append(buffer, static_cast<size_t>(n));
    if (contents.size() > max_bytes)
      throw FileReadError(path,
                          "file grew beyond " + SizeText(max_bytes) + " while it was read; " +
                              kind + " may have at most that",
                          false);
  }
  return contents;
}

}  // namespace simpartner
