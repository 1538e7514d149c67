// Model files are read from disk as regular files of at most
// kMaxModelFileBytes: a device, a FIFO, a directory or a too-large file is
// refused without being read (before: /dev/zero read until allocation
// failed, a FIFO blocked forever), as a world file and as the robot file a
// world includes. Real files in a temporary directory, the real /dev/zero
// and /dev/urandom.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

const char* kRobot = R"(<robot name="Tiny">
  <body type="Sphere" name="Ball"><mass>1</mass><radius>0.5</radius>
    <transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03><T10>0</T10><T11>1</T11>
    <T12>0</T12><T13>0.5</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation>
  </body>
</robot>
)";

std::string WorldWithRobot(const std::string& robot_file) {
  return "<world name=\"W\">\n  <robot name=\"R\" file=\"" + robot_file + "\"/>\n</world>\n";
}

class ModelFileRead : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sp_model_read_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "a_directory.xml");
    ASSERT_EQ(::mkfifo((dir_ / "fifo.xml").c_str(), 0600), 0);
    // Sparse: 65 MiB long, no blocks written.
    {
      std::ofstream big(dir_ / "big.xml");
    }
    std::filesystem::resize_file(dir_ / "big.xml", 65ull * 1024 * 1024);
    Write("robot.xml", kRobot);
    // A watchdog: a read that blocks (a FIFO opened without O_NONBLOCK)
    // ends the test binary instead of hanging it.
    ::alarm(30);
  }
  void TearDown() override {
    ::alarm(0);
    std::filesystem::remove_all(dir_);
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return Path(name);
  }

  std::filesystem::path dir_;
};

struct BadFile {
  const char* name;
  std::string path;
  std::string message;  // the diagnostic's message, exactly
};

std::vector<BadFile> BadFiles(const std::string& big_path, const std::string& fifo_path,
                              const std::string& dir_path) {
  return {
      {"/dev/zero", "/dev/zero",
       "not a regular file (character device); model files must be regular files"},
      {"/dev/urandom", "/dev/urandom",
       "not a regular file (character device); model files must be regular files"},
      {"FIFO", fifo_path, "not a regular file (FIFO); model files must be regular files"},
      {"directory", dir_path, "not a regular file (directory); model files must be regular files"},
      {"65 MiB sparse file", big_path,
       "file is 68157440 bytes (65 MiB); model files may have at most 67108864 bytes (64 MiB)"},
  };
}

TEST_F(ModelFileRead, WorldFileThatIsNotARegularFileOrTooLargeIsRefused) {
  for (const BadFile& bad : BadFiles(Path("big.xml"), Path("fifo.xml"), Path("a_directory.xml"))) {
    const WorldLoadResult result = LoadWorldFile(bad.path);
    EXPECT_FALSE(result.world.has_value()) << bad.name;
    ASSERT_EQ(result.diagnostics.size(), 1u) << bad.name << ": " << result.diagnostics.Format();
    EXPECT_EQ(result.diagnostics.items()[0].Format(), bad.path + ": " + bad.message) << bad.name;
  }
}

TEST_F(ModelFileRead, RobotFileThatIsNotARegularFileOrTooLargeIsRefused) {
  for (const BadFile& bad : BadFiles(Path("big.xml"), Path("fifo.xml"), Path("a_directory.xml"))) {
    const std::string world = Write("world.xml", WorldWithRobot(bad.path));
    const WorldLoadResult result = LoadWorldFile(world);
    EXPECT_FALSE(result.world.has_value()) << bad.name;
    ASSERT_EQ(result.diagnostics.size(), 2u) << bad.name << ": " << result.diagnostics.Format();
    // The world's <robot> (line 2) says it cannot load the file, and the
    // file's own diagnostic says why.
    EXPECT_EQ(result.diagnostics.items()[0].Format(),
              world + ":2: robot: robot 'R': cannot load '" + bad.path + "' (1 problem)")
        << bad.name;
    EXPECT_EQ(result.diagnostics.items()[1].Format(), bad.path + ": " + bad.message) << bad.name;
  }
}

TEST_F(ModelFileRead, MissingFileSaysWhy) {
  const WorldLoadResult world = LoadWorldFile(Path("missing.xml"));
  ASSERT_EQ(world.diagnostics.size(), 1u);
  EXPECT_EQ(world.diagnostics.items()[0].Format(),
            Path("missing.xml") + ": cannot read world file: No such file or directory");
  const RobotLoadResult robot = LoadRobotFile(Path("missing.xml"));
  ASSERT_EQ(robot.diagnostics.size(), 1u);
  EXPECT_EQ(robot.diagnostics.items()[0].Format(),
            Path("missing.xml") + ": cannot read robot file: No such file or directory");
}

// The limit is on the size: a regular file just under it is read (and then
// judged as XML), and the files of the ranges still load.
TEST_F(ModelFileRead, RegularFilesStillLoad) {
  const WorldLoadResult result = LoadWorldFile(Write("world.xml", WorldWithRobot("robot.xml")));
  ASSERT_TRUE(result.world.has_value()) << result.diagnostics.Format();
  ASSERT_EQ(result.world->robots.size(), 1u);
  EXPECT_EQ(result.world->robots[0].robot.bodies.size(), 1u);
  std::filesystem::resize_file(dir_ / "big.xml", static_cast<uintmax_t>(kMaxModelFileBytes));
  const WorldLoadResult at_limit = LoadWorldFile(Path("big.xml"));
  EXPECT_FALSE(at_limit.world.has_value());
  ASSERT_FALSE(at_limit.diagnostics.empty());
  EXPECT_EQ(at_limit.diagnostics.items()[0].Format().find("model files may have at most"),
            std::string::npos)
      << at_limit.diagnostics.Format();
}

}  // namespace
}  // namespace simpartner::model
