// ReadBoundedFile (common/bounded_file.h): a regular file within the limit
// is read whole; anything else is refused at once with the reason, and a
// file that is not there is "cannot open".
#include "simpartner/bounded_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "../support/test_dir.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

class BoundedFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_bounded_", 40); }
  void TearDown() override { fs::remove_all(dir_); }
  // The refusal's text, or "read" when it was read.
  static std::string Refusal(const fs::path& path, size_t limit, bool* cannot_open = nullptr) {
    try {
      ReadBoundedFile(path.string(), limit, "test files");
      return "read";
    } catch (const FileReadError& e) {
      EXPECT_EQ(e.path(), path.string());
      if (cannot_open) *cannot_open = e.cannot_open();
      return e.what();
    }
  }
  fs::path dir_;
};

TEST_F(BoundedFileTest, ARegularFileWithinTheLimitIsReadWhole) {
  const fs::path path = dir_ / "a.txt";
  const std::string text("key=1\n\0binary\xff", 14);
  std::ofstream(path, std::ios::binary) << text;
  EXPECT_EQ(ReadBoundedFile(path.string(), 14, "test files"), text);
  std::ofstream(dir_ / "empty.txt").close();
  EXPECT_EQ(ReadBoundedFile((dir_ / "empty.txt").string(), 0, "test files"), "");
  // The usual "no file": --params /dev/null.
  EXPECT_EQ(ReadBoundedFile("/dev/null", 0, "test files"), "");
}

TEST_F(BoundedFileTest, OneByteOverTheLimitIsRefusedWithBothSizes) {
  const fs::path path = dir_ / "big.txt";
  std::ofstream(path) << std::string(2 * 1048576 + 1, 'x');
  EXPECT_EQ(Refusal(path, 2 * 1048576),
            "file is 2097153 bytes (2.000000954 MiB); test files may have at most 2097152 bytes "
            "(2 MiB)");
}

TEST_F(BoundedFileTest, DevicesFifosAndDirectoriesAreRefusedBeforeAnyRead) {
  const fs::path fifo = dir_ / "fifo", link = dir_ / "zero";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", link);
  bool cannot_open = true;
  // A FIFO without a writer: no wait for one.
  EXPECT_EQ(Refusal(fifo, 100, &cannot_open),
            "not a regular file (FIFO); test files must be regular files");
  EXPECT_FALSE(cannot_open);
  EXPECT_EQ(Refusal("/dev/zero", 100),
            "not a regular file (character device); test files must be regular files");
  EXPECT_EQ(Refusal(link, 100),
            "not a regular file (character device); test files must be regular files");
  EXPECT_EQ(Refusal(dir_, 100), "not a regular file (directory); test files must be regular files");
}

TEST_F(BoundedFileTest, AMissingFileCannotBeOpened) {
  bool cannot_open = false;
  EXPECT_EQ(Refusal(dir_ / "none", 100, &cannot_open), "No such file or directory");
  EXPECT_TRUE(cannot_open);
}

}  // namespace
}  // namespace simpartner
