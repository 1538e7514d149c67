// Robot paths inside a world: relative to the world file, then the data
// roots (a world copied out of models/worlds keeps its shipped robot).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

namespace fs = std::filesystem;

TEST(DataLookup, ACopiedWorldFindsTheShippedRobotAndAMissingRobotNamesThePathsTried) {
  const fs::path dir = fs::temp_directory_path() / ("sp_data_lookup_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path copy = dir / "my_flat.xml";
  fs::copy_file(fs::path(SP_SOURCE_DIR) / "models/worlds/gen4_flat.xml", copy);
  const WorldLoadResult loaded = LoadWorldFile(copy.string());
  ASSERT_TRUE(loaded.world) << loaded.diagnostics.Format();
  ASSERT_EQ(loaded.world->robots.size(), 1u);
  EXPECT_EQ(loaded.world->robots[0].resolved_file,
            (fs::path(SP_SOURCE_DIR) / "models/robots/workpartner_gen4.xml").lexically_normal());

  std::ifstream in(copy);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = text.find("workpartner_gen4.xml");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("workpartner_gen4.xml").size(), "workpartner_gen9.xml");
  std::ofstream(dir / "gen9.xml") << text;
  const WorldLoadResult missing = LoadWorldFile((dir / "gen9.xml").string());
  EXPECT_FALSE(missing.world);
  const std::string message = missing.diagnostics.Format();
  EXPECT_NE(message.find("also looked for it at " +
                         (fs::path(SP_SOURCE_DIR) / "models/robots/workpartner_gen9.xml").string() +
                         " (source tree)"),
            std::string::npos)
      << message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace simpartner::model
