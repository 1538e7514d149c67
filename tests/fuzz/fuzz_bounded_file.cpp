// libFuzzer target: ReadBoundedFile (common/bounded_file.h), the one reader
// of every file a user names. The input chooses what the path is (a
// regular file of the remaining bytes, a FIFO without a writer, a
// directory, /dev/zero behind a symlink) and the size limit. Whatever it
// is, the reader returns at once: the bytes of a regular file within the
// limit, else FileReadError saying it was refused, never a hang (a FIFO)
// or an endless read (/dev/zero).
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "simpartner/bounded_file.h"

namespace {

namespace fs = std::filesystem;

// A folder of this run's own, removed when the fuzzer exits.
struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("sp_fuzz_bounded_" + std::to_string(::getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

const fs::path& Dir() {
  static const ScratchDir dir;
  return dir.path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  const int kind = data[0] % 4;
  const size_t limit = (static_cast<size_t>(data[1]) << 8 | data[2]) % 4096;
  const std::string contents(reinterpret_cast<const char*>(data + 3), size - 3);
  const fs::path path = Dir() / "input";
  std::error_code ignored;
  fs::remove_all(path, ignored);
  switch (kind) {
    case 0: std::ofstream(path, std::ios::binary) << contents; break;
    case 1: ::mkfifo(path.c_str(), 0600); break;
    case 2: fs::create_directory(path); break;
    case 3: fs::create_symlink("/dev/zero", path); break;
  }
  try {
    const std::string read = simpartner::ReadBoundedFile(path.string(), limit, "fuzz files");
    if (kind != 0 || contents.size() > limit || read != contents) __builtin_trap();
  } catch (const simpartner::FileReadError& e) {
    // Refused by type or size, never "cannot open": the file is there.
    if (e.cannot_open() || (kind == 0 && contents.size() <= limit)) __builtin_trap();
    if (e.path() != path.string() || std::string(e.what()).find("fuzz files") == std::string::npos)
      __builtin_trap();
  }
  return 0;
}
