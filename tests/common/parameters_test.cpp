#include "simpartner/parameters.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "simpartner/command_line.h"

namespace simpartner {
namespace {

ParameterSources FromFile(const std::string& file) {
  ParameterSources sources;
  sources.file = file;
  sources.file_given = true;
  return sources;
}

// Parses text and returns the diagnostics.
DiagnosticList Parse(const std::string& text, Parameters* params) {
  DiagnosticList diagnostics;
  ParseParametersText(text, "p.txt", params, &diagnostics);
  return diagnostics;
}

bool HasDiagnostic(const DiagnosticList& list, int line, const std::string& key,
                   const std::string& text) {
  for (const Diagnostic& d : list.items())
    if (d.line == line && d.element == key && d.message.find(text) != std::string::npos)
      return true;
  return false;
}

TEST(Parameters, OriginalKeysAndValues) {
  Parameters params;
  const DiagnosticList d = Parse(
      "# a comment\n"
      "dbname=wp\n"
      "dbserver = localhost\n"
      "log=0\n"
      "logEveryStep=1   # trailing comment\n"
      "environment=worlds/maze.xml\n"
      "stepsize=0.005\n"
      "contactMaxCorrectingVel=0.3\n"
      "contactSurfaceLayer=0.001\n"
      "autoDisableFlag=1\n"
      "globalERP=0.5\n"
      "globalCFM=1e-6\n"
      "stepper=quick\n",
      &params);
  ASSERT_TRUE(d.empty()) << d.Format();
  EXPECT_EQ(params.dbname, "wp");
  EXPECT_EQ(params.dbserver, "localhost");
  EXPECT_FALSE(params.log);
  EXPECT_TRUE(params.logEveryStep);
  // Relative paths are relative to the parameters file ("p.txt" is in ".").
  EXPECT_EQ(params.environment, "worlds/maze.xml");
  EXPECT_DOUBLE_EQ(params.stepsize, 0.005);
  EXPECT_DOUBLE_EQ(params.contactMaxCorrectingVel, 0.3);
  EXPECT_DOUBLE_EQ(params.contactSurfaceLayer, 0.001);
  EXPECT_TRUE(params.autoDisableFlag);
  EXPECT_DOUBLE_EQ(params.globalERP, 0.5);
  EXPECT_DOUBLE_EQ(params.globalCFM, 1e-6);
  EXPECT_EQ(params.stepper, "quick");
}

TEST(Parameters, ErrorsNameFileLineKeyAndRange) {
  Parameters params;
  const DiagnosticList d = Parse(
      "stepsize=0.5\n"         // out of range
      "globalERP=abc\n"        // not a number
      "stepSize=0.01\n"        // unknown (typo)
      "log=maybe\n"            // not a boolean
      "quickStepIterations=2.5\n"  // not an integer
      "stepper=fast\n"         // not a choice
      "just some words\n"      // no '='
      "globalCFM=nan\n"        // not finite
      "stepsize=0.002\n",      // set twice (first at line 1)
      &params);
  EXPECT_EQ(d.size(), 9u) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 1, "stepsize", "'0.5' is out of range (allowed: number 1e-05 to 0.1)"))
      << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 2, "globalERP", "'abc' is not a number")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 3, "stepSize", "did you mean 'stepsize'")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 4, "log", "not a boolean")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 5, "quickStepIterations", "not an integer")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 6, "stepper", "one of accurate quick")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 7, "", "expected key=value")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 8, "globalCFM", "not a finite number")) << d.Format();
  EXPECT_TRUE(HasDiagnostic(d, 9, "stepsize", "set twice (first at line 1)")) << d.Format();
  // Bad lines change nothing.
  EXPECT_DOUBLE_EQ(params.stepsize, Parameters().stepsize);
  EXPECT_DOUBLE_EQ(params.globalERP, Parameters().globalERP);
  // The formatted message has the compiler-like location prefix.
  EXPECT_EQ(d.items()[0].Format(),
            "p.txt:1: stepsize: value '0.5' is out of range (allowed: number 1e-05 to 0.1)");
}

TEST(Parameters, RangeEdgesAreInclusive) {
  Parameters params;
  EXPECT_TRUE(Parse("globalERP=0\n", &params).empty());
  EXPECT_TRUE(Parse("globalERP=1\n", &params).empty());
  EXPECT_FALSE(Parse("globalERP=1.0000001\n", &params).empty());
  EXPECT_FALSE(Parse("globalERP=-0.0000001\n", &params).empty());
  EXPECT_FALSE(Parse("maxContacts=0\n", &params).empty());
  EXPECT_FALSE(Parse("maxContacts=99999999999999999999\n", &params).empty());
}

class ParametersFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("sp_params_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "conf");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  std::filesystem::path dir_;
};

TEST_F(ParametersFiles, CommandLineOverridesFile) {
  const std::string file = Write("conf/run.txt", "stepsize=0.002\nenvironment=../worlds/w.xml\n");
  CommandLineSpec sim;
  sim.program = "sim";
  sim.options = {Switch("check", "check only")};
  sim.parameters = ParameterUse{};
  const CommandLine cl = ParseCommandLine(
      sim, {"--params", file, "--stepsize=0.004", "--check", "--lcm-url", "memq://"});
  EXPECT_TRUE(cl.Has("check"));
  const Parameters params = LoadParameters(cl.parameter_sources());
  EXPECT_DOUBLE_EQ(params.stepsize, 0.004);
  EXPECT_EQ(params.lcmUrl, "memq://");
  // Resolved against the directory of the file that set it.
  EXPECT_EQ(params.environment, (dir_ / "worlds/w.xml").lexically_normal().string());
}

// Editors on Windows save parameters.txt as UTF-8 with a byte order mark.
TEST_F(ParametersFiles, Utf8ByteOrderMarkAtStartIsAccepted) {
  const std::string file =
      Write("conf/bom.txt", "\xEF\xBB\xBF" "environment=../worlds/w.xml\nstepsize=0.002\n");
  const Parameters params = LoadParameters(FromFile(file));
  EXPECT_EQ(params.environment, (dir_ / "worlds/w.xml").lexically_normal().string());
  EXPECT_DOUBLE_EQ(params.stepsize, 0.002);
  // Only a mark at the very start is one; elsewhere the bytes are part of a key.
  Parameters inside;
  const DiagnosticList d = Parse("stepsize=0.002\n\xEF\xBB\xBF" "log=0\n", &inside);
  EXPECT_TRUE(HasDiagnostic(d, 2, "\xEF\xBB\xBF" "log", "unknown key")) << d.Format();
}

TEST_F(ParametersFiles, MissingGivenFileIsAnError) {
  const std::string missing = (dir_ / "nope.txt").string();
  try {
    LoadParameters(FromFile(missing));
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.diagnostics().items().at(0).file, missing);
    EXPECT_NE(std::string(e.what()).find("cannot open parameters file"), std::string::npos);
  }
}

// The joints' law is physical by default: a per-step globalERP or
// globalCFM would be ignored, so it is refused where it was set; with
// jointStiffness=0 it is the law.
TEST_F(ParametersFiles, PerStepJointLawOnlyWithoutJointStiffness) {
  const std::string file = Write("erp.txt", "stepsize=0.002\nglobalCFM=1e-6\n");
  try {
    LoadParameters(FromFile(file));
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const DiagnosticList& d = e.diagnostics();
    ASSERT_EQ(d.size(), 1u) << d.Format();
    EXPECT_EQ(d.items()[0].file, file);
    EXPECT_EQ(d.items()[0].line, 2);
    EXPECT_EQ(d.items()[0].element, "globalCFM");
    EXPECT_NE(d.items()[0].message.find("jointStiffness=0"), std::string::npos);
  }
  ParameterSources per_step = FromFile(file);
  per_step.overrides = {{"jointStiffness", "0"}};
  const Parameters params = LoadParameters(per_step);
  EXPECT_EQ(params.JointCFM(), 1e-6);
  EXPECT_EQ(params.JointERP(), 0.2);
}

// Physical: ERP and CFM of a spring k and damper c at step h (ODE's
// manual, "How To Use ERP and CFM"): the 0.2 and 1e-5 of the original at
// 1 ms, and the spring k = ERP / (h CFM) the same at every step.
TEST(Parameters, JointLawIsTheSameSpringAtAnyStep) {
  Parameters params;
  EXPECT_NEAR(params.JointERP(), 0.2, 1e-15);
  EXPECT_NEAR(params.JointCFM(), 1e-5, 1e-20);
  for (const double h : {0.0005, 0.001, 0.002, 0.01}) {
    params.stepsize = h;
    EXPECT_NEAR(params.JointERP() / (h * params.JointCFM()), 2e7, 1e-6) << "h " << h;
    EXPECT_NEAR((1.0 - params.JointERP()) / params.JointCFM(), 8e4, 1e-9) << "h " << h;
  }
}

TEST_F(ParametersFiles, FileAndCommandLineErrorsAreAllReported) {
  const std::string file = Write("bad.txt", "\n\nglobalERP=2\n");
  ParameterSources sources = FromFile(file);
  sources.overrides = {{"nokey", "1"}, {"stepsize", "x"}};
  try {
    LoadParameters(sources);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    const DiagnosticList& d = e.diagnostics();
    ASSERT_EQ(d.size(), 3u) << d.Format();
    EXPECT_EQ(d.items()[0].file, file);
    EXPECT_EQ(d.items()[0].line, 3);
    EXPECT_EQ(d.items()[0].element, "globalERP");
    EXPECT_EQ(d.items()[1].Format(), "command line: nokey: unknown key 'nokey'");
    EXPECT_EQ(d.items()[2].element, "stepsize");
  }
}

// Without --params, a program that reads no default file (the converter)
// gets the defaults and the overrides only.
TEST_F(ParametersFiles, NoDefaultFileMeansDefaultsAndOverrides) {
  Write("parameters.txt", "stepsize=0.002\n");
  const std::filesystem::path before = std::filesystem::current_path();
  std::filesystem::current_path(dir_);
  ParameterSources sources;
  sources.default_file = false;
  sources.overrides = {{"contactMu", "0.5"}};
  const Parameters without = LoadParameters(sources);
  sources.default_file = true;
  const Parameters with = LoadParameters(sources);
  std::filesystem::current_path(before);
  EXPECT_DOUBLE_EQ(without.stepsize, Parameters().stepsize);
  EXPECT_DOUBLE_EQ(without.contactMu, 0.5);
  EXPECT_DOUBLE_EQ(with.stepsize, 0.002);
  EXPECT_DOUBLE_EQ(with.contactMu, 0.5);
}

TEST(Parameters, FormatRoundTrips) {
  Parameters params;
  params.stepsize = 0.0025;
  params.stepper = "quick";
  params.dbname = "other";
  Parameters parsed;
  const DiagnosticList d = Parse(FormatParameters(params), &parsed);
  ASSERT_TRUE(d.empty()) << d.Format();
  EXPECT_EQ(FormatParameters(parsed), FormatParameters(params));
}

// The shipped parameters.txt documents every key and sets only valid values.
TEST(Parameters, ShippedFileDocumentsEveryKey) {
  const std::string path = std::string(SP_SOURCE_DIR) + "/parameters.txt";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream text;
  text << in.rdbuf();
  Parameters params;
  DiagnosticList d;
  ParseParametersText(text.str(), path, &params, &d);
  EXPECT_TRUE(d.empty()) << d.Format();
  std::set<std::string> mentioned;
  std::string line;
  std::istringstream lines(text.str());
  while (std::getline(lines, line)) {
    for (const std::string& key : ParameterKeys()) {
      if (line.find(key + "=") != std::string::npos) mentioned.insert(key);
    }
  }
  for (const std::string& key : ParameterKeys())
    EXPECT_TRUE(mentioned.count(key)) << "parameters.txt does not mention '" << key << "'";
}

// --help of a program lists the sections it reads: each key once, under its
// own section, and none of another; a misspelled section is caught.
TEST(Parameters, UsageListsOnlyTheGivenSections) {
  CommandLineSpec spec;
  spec.program = "viewer";
  spec.parameters = ParameterUse{{parameter_sections::kTransport}};
  const std::string viewer = FormatHelp(spec);
  EXPECT_NE(viewer.find("    lcmUrl="), std::string::npos) << viewer;
  EXPECT_EQ(viewer.find("stepsize="), std::string::npos) << viewer;
  EXPECT_EQ(viewer.find("dbname="), std::string::npos) << viewer;
  EXPECT_NE(viewer.find("other programs"), std::string::npos) << viewer;
  spec.parameters = ParameterUse{};
  const std::string all = FormatHelp(spec);
  for (const std::string& key : ParameterKeys())
    EXPECT_NE(all.find("    " + key + "="), std::string::npos) << key;
  EXPECT_THROW(DescribeParameters({"Trnasport"}), std::invalid_argument);
}

}  // namespace
}  // namespace simpartner
