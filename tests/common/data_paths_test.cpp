// The data lookup (data_paths.h): the order of the places, the first file
// that exists wins, and a miss names every full path.
#include "simpartner/data_paths.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace simpartner {
namespace {

namespace fs = std::filesystem;

class DataPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sp_data_paths_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "a/models/worlds");
    fs::create_directories(dir_ / "b/models/worlds");
    std::ofstream(dir_ / "a/models/worlds/w.xml") << "a";
    std::ofstream(dir_ / "b/models/worlds/w.xml") << "b";
    std::ofstream(dir_ / "b/models/worlds/only_b.xml") << "b";
    roots_ = {{(dir_ / "a").string(), "first"}, {(dir_ / "b").string(), "second"}};
    // "As given" is relative to the working directory: an empty one, so
    // that a run from the source tree (which has models/worlds) gives the
    // same answers as one from ctest's directory.
    fs::create_directories(dir_ / "cwd");
    previous_cwd_ = fs::current_path();
    fs::current_path(dir_ / "cwd");
  }
  void TearDown() override {
    fs::current_path(previous_cwd_);
    fs::remove_all(dir_);
  }

  fs::path dir_;
  fs::path previous_cwd_;
  std::vector<DataRoot> roots_;
};

TEST_F(DataPathsTest, CandidatesAreAsGivenThenEachRootWithAndWithoutTheKindDirectory) {
  const auto c = DataFileCandidates("x/w.xml", {"models/worlds"}, roots_);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c[0].path, (fs::current_path() / "x/w.xml").string());
  EXPECT_EQ(c[0].source, "as given");
  EXPECT_EQ(c[1].path, (dir_ / "a/x/w.xml").string());
  EXPECT_EQ(c[2].path, (dir_ / "a/models/worlds/w.xml").string());
  EXPECT_EQ(c[2].source, "first");
  EXPECT_EQ(c[3].path, (dir_ / "b/x/w.xml").string());
  EXPECT_EQ(c[4].path, (dir_ / "b/models/worlds/w.xml").string());
  EXPECT_EQ(c[4].source, "second");
}

TEST_F(DataPathsTest, TheFirstRootThatHasTheFileWins) {
  EXPECT_EQ(FindDataFile("w.xml", "world", {"models/worlds"}, roots_),
            (dir_ / "a/models/worlds/w.xml").string());
  EXPECT_EQ(FindDataFile("models/worlds/only_b.xml", "world", {}, roots_),
            (dir_ / "b/models/worlds/only_b.xml").string());
  // Present as given: the name itself, as the user wrote it.
  const fs::path absolute = dir_ / "b/models/worlds/w.xml";
  EXPECT_EQ(FindDataFile(absolute.string(), "world", {"models/worlds"}, roots_),
            absolute.string());
  EXPECT_EQ(FindDataDirectory("models/worlds", "worlds directory", roots_),
            (dir_ / "a/models/worlds").string());
}

TEST_F(DataPathsTest, AMissNamesTheFileAndEveryPathTried) {
  try {
    FindDataFile("nope.xml", "world", {"models/worlds"}, roots_);
    FAIL() << "no exception";
  } catch (const DataFileNotFound& e) {
    EXPECT_EQ(e.name(), "nope.xml");
    EXPECT_EQ(e.tried().size(), 5u);
    const std::string text = e.what();
    EXPECT_EQ(text.rfind("nope.xml: cannot read world file: not found; tried:\n", 0), 0u) << text;
    for (const char* p : {"a/nope.xml (first)", "a/models/worlds/nope.xml (first)",
                          "b/nope.xml (second)", "b/models/worlds/nope.xml (second)"})
      EXPECT_NE(text.find("  " + (dir_ / p).string() + "\n"), std::string::npos) << p << "\n"
                                                                                 << text;
  }
  // An absolute name is looked for there only.
  try {
    FindDataFile((dir_ / "nope.xml").string(), "world", {"models/worlds"}, roots_);
    FAIL() << "no exception";
  } catch (const DataFileNotFound& e) {
    EXPECT_EQ(e.tried().size(), 1u);
  }
}

TEST_F(DataPathsTest, SimpartnerDataComesFirstAndMayListSeveralDirectories) {
  const char* saved = std::getenv(kDataEnvironmentVariable);
  const std::string previous = saved ? saved : "";
  ::setenv(kDataEnvironmentVariable, ((dir_ / "b").string() + "::" + (dir_ / "a").string()).c_str(),
           1);
  const std::vector<DataRoot> roots = DataRoots();
  if (saved) ::setenv(kDataEnvironmentVariable, previous.c_str(), 1);
  else ::unsetenv(kDataEnvironmentVariable);
  ASSERT_GE(roots.size(), 3u);
  EXPECT_EQ(roots[0].directory, (dir_ / "b").string());
  EXPECT_EQ(roots[0].source, "SIMPARTNER_DATA");
  EXPECT_EQ(roots[1].directory, (dir_ / "a").string());
  // This test runs from the build tree: the sources come next.
  EXPECT_EQ(roots[2].directory, fs::path(SP_SOURCE_DIR).lexically_normal().string());
  EXPECT_EQ(roots[2].source, "source tree");
}

// The private server's files (simpartner-mariadb's directory): from the
// build tree, $SIMPARTNER_STATE, the working directory, the source tree;
// never ~/.local/state (that is an installed program's; installed_sim_test
// covers it).
TEST_F(DataPathsTest, PrivateServerFilesAreLookedForWhereTheScriptPutsThem) {
  const char* saved = std::getenv(kStateEnvironmentVariable);
  const std::string previous = saved ? saved : "";
  ::setenv(kStateEnvironmentVariable, (dir_ / "st").string().c_str(), 1);
  const std::vector<DataRoot> with = PrivateServerDirectories();
  ::unsetenv(kStateEnvironmentVariable);
  const std::vector<DataRoot> without = PrivateServerDirectories();
  if (saved) ::setenv(kStateEnvironmentVariable, previous.c_str(), 1);
  ASSERT_EQ(with.size(), 3u);
  EXPECT_EQ(with[0].directory, (dir_ / "st/mariadb").string());
  EXPECT_EQ(with[0].source, "SIMPARTNER_STATE");
  EXPECT_EQ(with[1].directory, (fs::current_path() / "state/mariadb").string());
  EXPECT_EQ(with[2].directory,
            (fs::path(SP_SOURCE_DIR) / "state/mariadb").lexically_normal().string());
  EXPECT_EQ(with[2].source, "source tree");
  ASSERT_EQ(without.size(), 2u);
  EXPECT_EQ(without[0].directory, with[1].directory);
  const auto c = PrivateServerFileCandidates("reader.cnf", with);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].path, (dir_ / "st/mariadb/reader.cnf").string());
  EXPECT_EQ(PrivateServerFileCandidates("/x/reader.cnf").size(), 1u);
}

}  // namespace
}  // namespace simpartner
