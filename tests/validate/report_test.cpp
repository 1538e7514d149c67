// The terminal lines, the Markdown report with its plots, and the command
// line of simpartner-validate.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "simpartner/validate/cli.h"
#include "simpartner/validate/report.h"
#include "../support/text_file.h"

namespace simpartner::validate {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    char pattern[] = "/tmp/validate-test-XXXXXX";
    path_ = mkdtemp(pattern);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

ExperimentResult Sample() {
  ExperimentResult r;
  r.name = "free_fall";
  r.title = "Free fall";
  r.checks.push_back(Relative("error slope", 0.004905, 0.004905, 0.01, "m/s"));
  r.checks.push_back(Relative("radius", 4.72, 4.01, 0.10, "m"));
  r.notes = "Why it is so.";
  Plot p;
  p.file = "free_fall.png";
  p.title = "error vs time";
  p.xlabel = "t [s]";
  p.ylabel = "m";
  p.series.push_back(Series{"error", {0, 1, 2}, {0, 0.0049, 0.0098}, "lines"});
  p.series.push_back(Series{"fit", {0, 2}, {0, 0.0098}, "dashed"});
  r.plots.push_back(p);
  return r;
}

using test_support::ReadText;

TEST(ValidateReport, OneLinePerCheckWithTheVerdict) {
  std::ostringstream out;
  PrintResult(Sample(), out);
  const std::string text = out.str();
  EXPECT_NE(text.find("free_fall"), std::string::npos);
  EXPECT_NE(text.find("error slope"), std::string::npos);
  EXPECT_NE(text.find("PASS"), std::string::npos);
  EXPECT_NE(text.find("FAIL"), std::string::npos);
  EXPECT_NE(text.find("±10 %"), std::string::npos);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2);
}

TEST(ValidateReport, AFailedRunIsOneFailLineWithTheReason) {
  ExperimentResult r;
  r.name = "pole_task";
  r.error = "pole_task.xml: the simulation faulted at t = 3 s";
  std::ostringstream out;
  PrintResult(r, out);
  EXPECT_NE(out.str().find("ERROR: pole_task.xml: the simulation faulted"), std::string::npos);
  EXPECT_NE(out.str().find("FAIL"), std::string::npos);
  EXPECT_FALSE(r.Passed());
}

TEST(ValidateReport, WritesMarkdownAndAPngPerPlot) {
  TempDir dir;
  WriteReport(dir.path().string(), {Sample()}, "simpartner-validate --report x", Parameters());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("| [free_fall](#free_fall) | error slope | 0.004905 m/s"), std::string::npos);
  EXPECT_NE(page.find("**FAIL**"), std::string::npos);
  EXPECT_NE(page.find("![error vs time](free_fall.png)"), std::string::npos);
  EXPECT_NE(page.find("Why it is so."), std::string::npos);
  EXPECT_NE(page.find("simpartner-validate --report x"), std::string::npos);
  // A real PNG: the signature and more than a header.
  const std::string png = ReadText(dir.path() / "free_fall.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(ValidateReport, AnUnwritableDirectoryIsAnError) {
  TempDir dir;
  std::ofstream(dir.path() / "file") << "x";
  try {
    WriteReport((dir.path() / "file" / "sub").string(), {Sample()}, "cmd", Parameters());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create the report directory"), std::string::npos);
  }
}

int RunCli(const std::vector<std::string>& args, std::string* out, std::string* err) {
  std::ostringstream o, e;
  const int status = RunValidate(args, o, e);
  *out = o.str();
  *err = e.str();
  return status;
}

TEST(ValidateCommandLine, ListsEveryExperimentOfSpec8AndOurs) {
  std::string out, err;
  ASSERT_EQ(RunCli({"--list"}, &out, &err), 0) << err;
  for (const char* name :
       {"free_fall", "free_fall_thrown", "sliding_cube", "two_spheres", "circle_equal",
        "circle_differential", "scanner", "pole_task", "skid", "caterpillar", "rolking",
        "gen4_loads", "test_track", "rolling_sphere", "pendulum_energy"})
    EXPECT_NE(out.find(std::string(name) + (std::string(name) == "skid" ? " (slow)" : "")),
              std::string::npos)
        << name;
}

TEST(ValidateCommandLine, UnknownExperimentIsNamed) {
  std::string out, err;
  EXPECT_EQ(RunCli({"--only", "free_fal"}, &out, &err), 2);
  EXPECT_NE(err.find("--only free_fal: no such experiment"), std::string::npos) << err;
  EXPECT_NE(err.find("free_fall"), std::string::npos);
}

TEST(ValidateCommandLine, BadModelsDirectoryAndBadParameter) {
  std::string out, err;
  EXPECT_EQ(RunCli({"--models", "/nonexistent", "--only", "free_fall"}, &out, &err), 2);
  EXPECT_NE(err.find("--models /nonexistent: no worlds/ directory"), std::string::npos) << err;
  EXPECT_EQ(RunCli({"--stepsize=0.5"}, &out, &err), 2);
  EXPECT_NE(err.find("stepsize"), std::string::npos) << err;
  EXPECT_EQ(RunCli({"extra"}, &out, &err), 2);
  EXPECT_NE(err.find("unexpected argument 'extra'"), std::string::npos) << err;
}

TEST(ValidateCommandLine, RunsOneExperimentAndExitsZeroWhenItPasses) {
  std::string out, err;
  const int status = RunCli({"--only", "free_fall_thrown", "--params", "/dev/null"}, &out, &err);
  EXPECT_EQ(status, 0) << out << err;
  EXPECT_NE(out.find("free_fall_thrown"), std::string::npos);
  EXPECT_NE(out.find("1 of 1 experiments passed"), std::string::npos) << out;
}

TEST(ValidateCommandLine, ExitsOneWhenARunFails) {
  // The thrown body flies at 14 m/s: with a 5 m/s explosion bound the sim
  // faults, and the experiment fails with the sim's reason.
  std::string out, err;
  const int status = RunCli({"--only", "free_fall_thrown", "--params", "/dev/null",
                          "--maxLinearVelocity=5"},
                         &out, &err);
  EXPECT_EQ(status, 1) << out << err;
  EXPECT_NE(out.find("ERROR: free_fall_thrown.xml: the simulation faulted"), std::string::npos)
      << out;
  EXPECT_NE(out.find("0 of 1 experiments passed"), std::string::npos) << out;
}

TEST(ValidateCommandLine, HelpListsTheFlags) {
  std::string out, err;
  ASSERT_EQ(RunCli({"--help"}, &out, &err), 0);
  for (const char* flag : {"--only", "--report", "--fast", "--list", "--models"})
    EXPECT_NE(out.find(flag), std::string::npos) << flag;
}

}  // namespace
}  // namespace simpartner::validate
