// Every program that reads a file a user names, given /dev/zero, a FIFO
// without a writer and a settings file of 2 MiB: each refuses it at once
// (within the test's 30 s; before, /dev/zero was read without end and a
// FIFO hung the program, which then ignored SIGTERM), exits non-zero and
// names the file and why.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "../support/processes.h"
#include "../support/programs.h"
#include "../support/test_dir.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

struct Reader {
  const char* program;
  std::vector<std::string> args;  // "{F}" stands for the file
  bool settings;                  // capped at 1 MiB (else a model-sized cap)
};

std::vector<Reader> Readers() {
  const std::string world = test_support::SourceDir() + "/models/worlds/gen4_flat.xml";
  return {
      {"simpartner-sim", {"--params", "{F}", "--check"}, true},
      {"simpartner-sim", {"--environment={F}", "--check"}, false},
      {"simpartner-logger", {"--params", "/dev/null", "--db-options", "{F}"}, true},
      {"simpartner-query", {"--params", "/dev/null", "--db-options", "{F}", "list"}, true},
      {"simpartner-sequencer", {"--check", "{F}"}, false},
      {"simpartner-teleop", {"--check", "--environment", world, "--mapping", "{F}"}, true},
      {"simpartner-batch", {"{F}"}, false},
  };
}

class HostileFilesTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test_support::FreshTestDir("sp_hostile_files_", 30); }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // Runs each reader on `file`; each must end, non-zero, printing `expected`.
  void ExpectEachRefuses(const std::string& file, const std::string& expected, bool settings_only) {
    int i = 0;
    for (const Reader& r : Readers()) {
      if (settings_only && !r.settings) continue;
      std::vector<std::string> args = r.args;
      for (std::string& a : args)
        if (const size_t at = a.find("{F}"); at != std::string::npos) a.replace(at, 3, file);
      const test_support::ProgramRun run =
          test_support::RunToEnd(test_support::BuiltCommand(r.program, args),
                                 (dir_ / ("run" + std::to_string(i++) + ".log")).string(),
                                 std::chrono::seconds(30));
      const std::string what = std::string(r.program) + " " + args[args.size() > 1 ? 1 : 0];
      EXPECT_NE(run.status, -1) << what << " still ran after 30 s on " << file;
      EXPECT_NE(run.status, 0) << what << "\n" << run.output;
      EXPECT_NE(run.output.find(file), std::string::npos) << what << "\n" << run.output;
      EXPECT_NE(run.output.find(expected), std::string::npos) << what << "\n" << run.output;
    }
  }
  fs::path dir_;
};

TEST_F(HostileFilesTest, DevZeroIsRefusedByEveryReader) {
  ExpectEachRefuses("/dev/zero", "not a regular file (character device)", false);
}

TEST_F(HostileFilesTest, AFifoWithoutAWriterHangsNoReader) {
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  ExpectEachRefuses(fifo.string(), "not a regular file (FIFO)", false);
}

TEST_F(HostileFilesTest, ASettingsFileOverOneMebibyteIsRefused) {
  const fs::path big = dir_ / "big.txt";
  std::ofstream(big) << std::string(1048577, '#');
  ExpectEachRefuses(big.string(), "may have at most 1048576 bytes (1 MiB)", true);
}

}  // namespace
}  // namespace simpartner
