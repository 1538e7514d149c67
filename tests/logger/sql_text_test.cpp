// SQL text of the batches (numbers exact, strings escaped) and where the
// logger connects (parameters + option file), with every configuration
// error naming its key or file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "simpartner/logger/db.h"
#include "simpartner/logger/logger_config.h"
#include "simpartner/logger/sql_text.h"

namespace simpartner::logger {
namespace {

TEST(SqlTextTest, DoublesReadBackExactly) {
  for (double v : {0.0, -0.0, 1.0, 0.1, -9.81, 1e-300, 5e-324, 1.7976931348623157e308,
                   0.7149999999812345, 3.141592653589793}) {
    std::string text;
    AppendDouble(&text, v);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
    EXPECT_EQ(text.find(' '), std::string::npos);
  }
  std::string text;
  AppendDouble(&text, std::numeric_limits<double>::infinity());
  EXPECT_EQ(text, "NULL");
}

TEST(SqlTextTest, StringsAreQuotedAndEscaped) {
  EXPECT_EQ(Quoted("Wheel1"), "'Wheel1'");
  EXPECT_EQ(Quoted("it's"), "'it\\'s'");
  EXPECT_EQ(Quoted("a\\b"), "'a\\\\b'");
  EXPECT_EQ(Quoted(std::string("x\0y\n\r\"\032", 7)), "'x\\0y\\n\\r\\\"\\Z'");
  EXPECT_EQ(Quoted("'; DROP TABLE Pose; --"), "'\\'; DROP TABLE Pose; --'");
  std::string tsv;
  AppendTsvField(&tsv, "a\tb\nc\\d");
  EXPECT_EQ(tsv, "a\\tb\\nc\\\\d");
}

class DbTargetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("sp_dbtarget_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string WriteOptions(const std::string& text, mode_t mode = 0600) {
    const std::string path = (dir_ / "client.cnf").string();
    std::ofstream(path) << text;
    ::chmod(path.c_str(), mode);
    return path;
  }
  static std::string ErrorOf(const Parameters& p, const std::string& file) {
    try {
      ResolveDbTarget(p, file, "/nonexistent/state/mariadb/logger.cnf", nullptr);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  }
  std::filesystem::path dir_;
};

TEST_F(DbTargetTest, SocketFromTheOptionFileAndServerFromTheParameters) {
  const std::string file = WriteOptions("[client]\nsocket = /run/x.sock\nuser=u\npassword=secret\n");
  Parameters p;
  std::vector<std::string> warnings;
  DbTarget t = ResolveDbTarget(p, file, "", &warnings);
  EXPECT_EQ(t.Server(), "unix:///run/x.sock");
  EXPECT_EQ(t.database, "simpartner");
  EXPECT_TRUE(warnings.empty());
  p.dbserver = "db.example.org:3307";
  p.dbname = "runs";
  t = ResolveDbTarget(p, file, "", &warnings);
  EXPECT_EQ(t.Server(), "tcp://db.example.org:3307");
  EXPECT_EQ(t.database, "runs");
  p.dbserver = "/tmp/other.sock";
  EXPECT_EQ(ResolveDbTarget(p, file, "", &warnings).Server(), "unix:///tmp/other.sock");
}

TEST_F(DbTargetTest, ConfigurationErrorsNameTheKeyOrFile) {
  Parameters p;
  EXPECT_NE(ErrorOf(p, "").find("/nonexistent/state/mariadb/logger.cnf: dbserver: dbserver is empty, "
                                "so the private server's option file is used, but it is in none of "
                                "these places:\n  /nonexistent/state/mariadb/logger.cnf (as given)\n"
                                "start the server with simpartner-mariadb start"),
            std::string::npos) << ErrorOf(p, "");
  p.dbserver = "db:3306";
  EXPECT_NE(ErrorOf(p, "").find("dbserver: server 'db:3306' needs credentials: pass --db-options"),
            std::string::npos) << ErrorOf(p, "");
  const std::string file = WriteOptions("[client]\nuser=u\n");
  p.dbserver = "db:http";
  EXPECT_NE(ErrorOf(p, file).find("dbserver: port 'http' is not a number from 1 to 65535"),
            std::string::npos) << ErrorOf(p, file);
  p.dbserver = "";
  EXPECT_NE(ErrorOf(p, file).find(file + ": socket: names neither socket= nor host="),
            std::string::npos) << ErrorOf(p, file);
  p.dbname = "a`b";
  EXPECT_NE(ErrorOf(p, file).find("dbname: value 'a`b' has a character"), std::string::npos);
  const std::string no_user = WriteOptions("[client]\nsocket=/x.sock\n");
  p = Parameters();
  EXPECT_NE(ErrorOf(p, no_user).find(no_user + ": user: no user= in its [client] group"),
            std::string::npos) << ErrorOf(p, no_user);
}

TEST_F(DbTargetTest, OptionFileReadableByOthersIsAWarningAndThePasswordIsNeverShown) {
  const std::string file = WriteOptions("[client]\nsocket=/x.sock\nuser=u\npassword=topsecret\n", 0644);
  std::vector<std::string> warnings;
  const DbTarget t = ResolveDbTarget(Parameters(), file, "", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("readable by others (mode 0644)"), std::string::npos) << warnings[0];
  EXPECT_EQ(warnings[0].find("topsecret"), std::string::npos);
  EXPECT_EQ(t.Server().find("topsecret"), std::string::npos);
}

TEST(LoggerConfigTest, FlagsAndParameters) {
  const CommandLine cl = ParseCommandLine(
      LoggerCommandLine(), {"--params", "/dev/null", "--logEveryStep=0", "--logInterval=25", "--insert",
                            "loaddata", "--spool", "/tmp/s", "--db-options", "/dev/null",
                            "--dbserver=/x.sock"});
  const Parameters params = LoadParameters(cl.parameter_sources());
  try {
    MakeLoggerOptions(cl, params, nullptr);
    FAIL() << "/dev/null has no user";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/null: user: no user="), std::string::npos) << e.what();
  }
  auto refusal = [](const std::vector<std::string>& args) {
    try {
      ParseCommandLine(LoggerCommandLine(), args);
    } catch (const CommandLineError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refusal({"--insert", "fast"}), "--insert: value 'fast' is not auto, multirow or loaddata");
  EXPECT_EQ(refusal({"--queue-mb", "-3"}), "--queue-mb: value '-3' is not a number above 0 and at most 65536");
}

}  // namespace
}  // namespace simpartner::logger
