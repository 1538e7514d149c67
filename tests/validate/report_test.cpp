// The terminal lines, the Markdown report with its plots, and the command
// line of simpartner-validate.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "simpartner/validate/cli.h"
#include "simpartner/validate/explanations.h"
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
  r.engine = "ode";
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

TEST(ValidateReport, LinesNameTheEngineWhenAsked) {
  ExperimentResult r = Sample();
  r.engine = "mujoco";
  std::ostringstream plain, named;
  PrintResult(r, plain);
  PrintResult(r, named, true);
  EXPECT_EQ(plain.str().find("mujoco"), std::string::npos) << plain.str();
  std::istringstream lines(named.str());
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count)
    EXPECT_EQ(line.rfind("free_fall            mujoco error slope", 0) == 0 ||
                  line.rfind("free_fall            mujoco radius", 0) == 0,
              true)
        << line;
  EXPECT_EQ(count, 2);
}

TEST(ValidateReport, TalliesCountPassedExperimentsPerEngineInOrder) {
  // Sample()'s first check passes, its second fails.
  auto on = [](const char* engine, size_t checks, int64_t steps, double seconds) {
    ExperimentResult r = Sample();
    r.engine = engine;
    r.checks.resize(checks);
    r.stepping = StepTiming{steps, seconds};
    return r;
  };
  // ODE: 3,000 steps in 6 ms, 2 µs each; MuJoCo: 4,000 steps in 12 ms, 3 µs.
  const std::vector<ExperimentResult> results = {
      on("ode", 1, 1000, 0.002), on("mujoco", 1, 1000, 0.001), on("ode", 1, 1000, 0.002),
      on("mujoco", 2, 2000, 0.010), on("ode", 1, 1000, 0.002), on("mujoco", 1, 1000, 0.001)};
  const std::vector<EngineTally> tallies = TallyByEngine(results);
  ASSERT_EQ(tallies.size(), 2u);
  EXPECT_EQ(tallies[0].engine, "ode");
  EXPECT_EQ(tallies[0].passed, 3);
  EXPECT_EQ(tallies[0].run, 3);
  EXPECT_EQ(tallies[1].engine, "mujoco");
  EXPECT_EQ(tallies[1].passed, 2);
  EXPECT_EQ(tallies[1].run, 3);
  std::ostringstream out;
  PrintTallies(tallies, out);
  EXPECT_EQ(out.str(),
            "3 of 3 experiments passed on ODE (mean 2.00 µs per step)\n"
            "2 of 3 experiments passed on MuJoCo (mean 3.00 µs per step)\n");
  EXPECT_EQ(MicrosecondsText(183.4), "183");
  EXPECT_EQ(MicrosecondsText(24.14), "24.1");
  EXPECT_EQ(MicrosecondsText(0.354), "0.35");
  EXPECT_EQ(MicrosecondsText(std::nan("")), "-");
}

TEST(ValidateReport, WritesMarkdownAndAPngPerPlot) {
  TempDir dir;
  WriteReport(dir.path().string(), {Sample()}, "simpartner-validate --report x", Parameters());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("| [free_fall](#free_fall) | error slope | 0.004905 m/s | ±1 % | "
                      "0.004905 m/s PASS |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| [free_fall](#free_fall) | radius | 4.01 m | ±10 % | 4.72 m **FAIL** (not yet "
                      "explained) |"),
            std::string::npos)
      << page;
  EXPECT_EQ(page.find("MuJoCo"), std::string::npos);
  EXPECT_NE(page.find("![error vs time](free_fall.png)"), std::string::npos);
  EXPECT_NE(page.find("Why it is so."), std::string::npos);
  EXPECT_NE(page.find("simpartner-validate --report x"), std::string::npos);
  // A real PNG: the signature and more than a header.
  const std::string png = ReadText(dir.path() / "free_fall.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

// The same experiment on ODE (both checks pass: 4.02 m is within 10 % of
// 4.01 m) and on MuJoCo (4.72 m is not).
std::vector<ExperimentResult> OnBothEngines() {
  ExperimentResult ode = Sample();
  ode.checks[1] = Relative("radius", 4.02, 4.01, 0.10, "m");
  ode.stepping = StepTiming{2000, 0.001};  // 0.5 µs a step
  ExperimentResult mujoco = Sample();
  mujoco.engine = "mujoco";
  mujoco.stepping = StepTiming{2000, 0.004};  // 2 µs
  return {ode, mujoco};
}

TEST(ValidateReport, BothEnginesGetAColumnEachAndTheirOwnPlots) {
  TempDir dir;
  WriteReport(dir.path().string(), OnBothEngines(), "simpartner-validate --engine both",
              Parameters());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("Experiments passed: ODE 1 of 1, MuJoCo 0 of 1."), std::string::npos)
      << page;
  EXPECT_NE(page.find("| experiment | ODE | µs per step | MuJoCo | µs per step |"),
            std::string::npos);
  EXPECT_NE(page.find("| [free_fall](#free_fall) | PASS | 0.50 | **FAIL** | 2.00 |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| experiment | check | target | tolerance | ODE | MuJoCo |"),
            std::string::npos);
  EXPECT_NE(page.find("| [free_fall](#free_fall) | radius | 4.01 m | ±10 % | 4.02 m PASS | "
                      "4.72 m **FAIL** (not yet explained) |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("![error vs time](free_fall.png)"), std::string::npos);
  EXPECT_NE(page.find("![error vs time](free_fall_mujoco.png)"), std::string::npos);
  EXPECT_EQ(ReadText(dir.path() / "free_fall_mujoco.png").substr(1, 3), "PNG");
  EXPECT_EQ(ReadText(dir.path() / "free_fall.png").substr(1, 3), "PNG");
}

TEST(ValidateReport, AnExperimentAnEngineCannotRunIsNotApplicableNotFailed) {
  std::vector<ExperimentResult> results = OnBothEngines();
  results[1].checks.clear();
  results[1].plots.clear();
  results[1].stepping = StepTiming{};
  results[1].not_applicable = "the engine does not model it";
  TempDir dir;
  WriteReport(dir.path().string(), results, "simpartner-validate --engine both", Parameters());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("Experiments passed: ODE 1 of 1, MuJoCo 0 of 0 (1 not applicable)."),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| [free_fall](#free_fall) | PASS | 0.50 | n/a | - |"), std::string::npos)
      << page;
  EXPECT_NE(page.find("| 4.02 m PASS | n/a |"), std::string::npos) << page;
  EXPECT_NE(page.find("MuJoCo: not applicable: the engine does not model it."),
            std::string::npos)
      << page;
  EXPECT_EQ(page.find("free_fall_mujoco.png"), std::string::npos);
  std::ostringstream line, tally;
  PrintResult(results[1], line, true);
  EXPECT_EQ(line.str(), "free_fall            mujoco NOT APPLICABLE: the engine does not model it\n");
  PrintTallies(TallyByEngine(results), tally);
  EXPECT_NE(tally.str().find("0 of 0 experiments passed on MuJoCo, 1 not applicable"),
            std::string::npos)
      << tally.str();
}

TEST(ValidateReport, AnEnginesOwnTargetShowsInItsCell) {
  // A target computed from each run (a steady state from the run's own
  // loads): 4.72 m is within 2 % of ODE's 4.69 m but not of MuJoCo's 4.61 m.
  std::vector<ExperimentResult> results = OnBothEngines();
  results[0].checks = {Relative("steady state", 4.72, 4.69, 0.02, "m")};
  results[1].checks = {Relative("steady state", 4.74, 4.61, 0.02, "m")};
  TempDir dir;
  WriteReport(dir.path().string(), results, "cmd", Parameters());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("| [free_fall](#free_fall) | steady state | 4.69 m | ±2 % | 4.72 m PASS | "
                      "4.74 m (target 4.61 m ±2 %) **FAIL** (not yet explained) |"),
            std::string::npos)
      << page;
}

TEST(ValidateReport, ARunThatFailedOnOneEngineKeepsTheOthersFigures) {
  std::vector<ExperimentResult> results = OnBothEngines();
  results[1].checks.clear();
  results[1].plots.clear();
  results[1].error = "MuJoCo failed: a loop";
  TempDir dir;
  WriteReport(dir.path().string(), results, "cmd", Parameters());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("| [free_fall](#free_fall) | the run: MuJoCo failed: a loop | | | - | "
                      "**FAIL** (not yet explained) |"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("| [free_fall](#free_fall) | radius | 4.01 m | ±10 % | 4.02 m PASS | "
                      "run failed **FAIL** |"),
            std::string::npos)
      << page;
}

TEST(ValidateExplanations, TheShippedTableNamesKnownExperimentsAndEngines) {
  EXPECT_EQ(ExplanationProblems(Explanations()), std::vector<std::string>{});
  const std::vector<Explanation> bad = {
      {"circle_equl", "radius", "mujoco", std::string(40, 'x')},
      {"circle_equal", "radius", "bullet", "soft"}};
  EXPECT_EQ(ExplanationProblems(bad),
            (std::vector<std::string>{
                "circle_equl / 'radius' / mujoco: no such experiment",
                "circle_equal / 'radius' / bullet: no such engine",
                "circle_equal / 'radius' / bullet: the cause 'soft' is too short to be one"}));
}

// One cause for the circle's thesis-friction checks on MuJoCo.
const std::vector<Explanation>& CircleTable() {
  static const std::vector<Explanation> table = {
      {"circle_equal", "thesis friction", "mujoco", "Because of the friction cone, here."}};
  return table;
}

// circle_equal's thesis-friction check passing on ODE and, on MuJoCo,
// passing or failing; an isotropic check failing on MuJoCo.
std::vector<ExperimentResult> CircleOnBothEngines(bool mujoco_passes) {
  ExperimentResult ode;
  ode.name = "circle_equal";
  ode.engine = "ode";
  ode.checks.push_back(Relative("radius, thesis friction", 4.0, 4.0, 0.01, "m"));
  ode.checks.push_back(Relative("radius, isotropic mu 1", 1.0, 1.0, 0.01, "m"));
  ExperimentResult mujoco = ode;
  mujoco.engine = "mujoco";
  mujoco.checks[0] = Relative("radius, thesis friction", mujoco_passes ? 4.0 : 4.5, 4.0, 0.01, "m");
  mujoco.checks[1] = Relative("radius, isotropic mu 1", 2.0, 1.0, 0.01, "m");
  return {ode, mujoco};
}

TEST(ValidateExplanations, AFailingCheckLinksToItsEnginesExplanation) {
  const Explanation* why = &CircleTable().front();
  EXPECT_EQ(Explain(CircleTable(), "circle_equal", "radius, thesis friction", "mujoco"), why);
  EXPECT_EQ(Explain(CircleTable(), "circle_equal", "radius, thesis friction", "ode"), nullptr);
  EXPECT_EQ(Explain(CircleTable(), "circle_equal", "radius, isotropic mu 1", "mujoco"), nullptr);
  TempDir dir;
  WriteReport(dir.path().string(), CircleOnBothEngines(false), "cmd", Parameters(),
              CircleTable());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_NE(page.find("| 4 m PASS | 4.5 m **FAIL** ([why](#why-1)) |"), std::string::npos)
      << page;
  EXPECT_NE(page.find("| 1 m PASS | 2 m **FAIL** (not yet explained) |"), std::string::npos)
      << page;
  EXPECT_NE(page.find("<a id=\"why-1\"></a>\n**1.** Because of the friction cone, here.\n\n"
                      "- [circle_equal](#circle_equal) on MuJoCo, radius, thesis friction: 4.5 m "
                      "against 4 m ±1 %\n"),
            std::string::npos)
      << page;
  EXPECT_NE(page.find("- [circle_equal](#circle_equal) on MuJoCo, radius, isotropic mu 1: 2 m "
                      "against 1 m ±1 %\n"),
            std::string::npos)
      << page;
}

TEST(ValidateExplanations, NeverShowBesideAPass) {
  std::vector<ExperimentResult> results = CircleOnBothEngines(true);
  results[1].checks.pop_back();  // only the explained check, and it passes
  TempDir dir;
  WriteReport(dir.path().string(), results, "cmd", Parameters(), CircleTable());
  const std::string page = ReadText(dir.path() / "README.md");
  EXPECT_EQ(page.find("Why checks fail"), std::string::npos) << page;
  EXPECT_EQ(page.find("friction cone"), std::string::npos);
  EXPECT_EQ(page.find("**FAIL**"), std::string::npos);
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
        "gen4_loads", "test_track", "rolling_sphere", "pendulum_energy", "soil_sinkage",
        "soil_compaction", "soil_traction", "soil_step_size", "soil_multipass", "soil_robot",
        "soil_measured", "sensors"})
    EXPECT_NE(out.find(std::string(name) + (std::string(name) == "skid" ? " (slow)" : "")),
              std::string::npos)
        << name;
  // Titles say what an experiment is, not which tracker entry asked for it.
  EXPECT_EQ(out.find("Issue"), std::string::npos) << out;
  EXPECT_NE(out.find("soil_sinkage"), std::string::npos);
  EXPECT_NE(out.find("On soil: a rigid wheel's static sinkage"), std::string::npos) << out;
  EXPECT_NE(out.find("Field sensors: IMU, encoder, lidar and GNSS"), std::string::npos) << out;
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

// The closing lines of the engines named, one after the other, each
// "P of R experiments passed on ENGINE (mean X µs per step)" with X a
// number or "-" (it made no step). (No std::regex: GCC 12 warns inside it
// in the sanitized build.)
struct Tally {
  int passed, run;
  const char* engine;
};
bool HasTallies(const std::string& out, const std::vector<Tally>& tallies) {
  size_t at = std::string::npos;
  for (const Tally& t : tallies) {
    const std::string head = std::to_string(t.passed) + " of " + std::to_string(t.run) +
                             " experiments passed on " + t.engine + " (mean ";
    const size_t found = out.find(head, at == std::string::npos ? 0 : at);
    if (found == std::string::npos || (at != std::string::npos && found != at)) return false;
    const size_t end = out.find(" µs per step)\n", found + head.size());
    if (end == std::string::npos) return false;
    const std::string mean = out.substr(found + head.size(), end - found - head.size());
    if (mean != "-" && mean.find_first_not_of("0123456789.") != std::string::npos) return false;
    at = end + std::string(" µs per step)\n").size();
  }
  return true;
}

// The lines of `text` that start with `prefix`.
int LinesStartingWith(const std::string& text, const std::string& prefix) {
  std::istringstream lines(text);
  int count = 0;
  for (std::string line; std::getline(lines, line);) count += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return count;
}

TEST(ValidateEngines, BothRunsEachCheckOnOdeThenMujoco) {
  // SPEC 8's free fall: four step sizes at g 9.81 and one at g 50, five
  // checks. Both engines integrate semi-implicitly (v += g dt, x += v dt),
  // so both show the error slope g dt / 2 and pass.
  std::string out, err;
  const int status =
      RunCli({"--only", "free_fall", "--engine", "both", "--params", "/dev/null"}, &out, &err);
  EXPECT_EQ(status, 0) << out << err;
  EXPECT_EQ(LinesStartingWith(out, "free_fall            ode    error slope, g "), 5) << out;
  EXPECT_EQ(LinesStartingWith(out, "free_fall            mujoco error slope, g "), 5) << out;
  EXPECT_LT(out.find("free_fall            ode"), out.find("free_fall            mujoco"));
  EXPECT_TRUE(HasTallies(out, {{1, 1, "ODE"}, {1, 1, "MuJoCo"}}))
      << out;
}

TEST(ValidateEngines, TheDefaultRunIsOdeAloneWithoutAnEngineColumn) {
  std::string out, err;
  ASSERT_EQ(RunCli({"--only", "free_fall_thrown", "--params", "/dev/null"}, &out, &err), 0)
      << out << err;
  EXPECT_EQ(LinesStartingWith(out, "free_fall_thrown     largest horizontal error"), 1) << out;
  EXPECT_EQ(out.find("mujoco"), std::string::npos) << out;
  EXPECT_EQ(out.find("MuJoCo"), std::string::npos) << out;
  EXPECT_TRUE(HasTallies(out, {{1, 1, "ODE"}})) << out;
}

TEST(ValidateEngines, TheParameterFormStillPicksTheEngine) {
  std::string out, err;
  ASSERT_EQ(RunCli({"--only", "free_fall_thrown", "--params", "/dev/null", "--engine=mujoco"},
                   &out, &err),
            0)
      << out << err;
  EXPECT_EQ(LinesStartingWith(out, "free_fall_thrown     largest horizontal error"), 1) << out;
  EXPECT_TRUE(HasTallies(out, {{1, 1, "MuJoCo"}})) << out;
  ASSERT_EQ(RunCli({"--engine=mujoco", "--print-parameters", "--params", "/dev/null"}, &out, &err),
            0);
  EXPECT_NE(out.find("engine=mujoco"), std::string::npos) << out;
}

TEST(ValidateEngines, AnUnknownEngineIsAUsageError) {
  std::string out, err;
  EXPECT_EQ(RunCli({"--engine", "bullet", "--only", "free_fall"}, &out, &err), 2);
  EXPECT_NE(err.find("--engine"), std::string::npos) << err;
  EXPECT_NE(err.find("bullet"), std::string::npos) << err;
}

// models/ with a free_fall_thrown.xml whose particle flies as the shipped
// one, beside two bodies hanging from the world and from each other: a
// loop, which ODE runs and the MuJoCo engine refuses (it hangs bodies in
// a tree).
fs::path ModelsWithALoop(const fs::path& dir) {
  fs::create_directories(dir / "worlds");
  std::string world = ReadText(fs::path(SP_SOURCE_DIR) / "models/worlds/free_fall_thrown.xml");
  const std::string end = "</world>";
  const size_t at = world.rfind(end);
  auto body = [](const char* name, int x) {
    return std::string("<object type=\"Body\" name=\"") + name +
           "\"><mass>1</mass><transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>" +
           std::to_string(x) + "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>1</T13>" +
           "<T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation></object>\n";
  };
  auto joint = [](const char* name, const char* a, const char* b, double x, double y) {
    return std::string("<joint type=\"Ball\" name=\"") + name + "\"><body1>" + a +
           "</body1><body2>" + b + "</body2><anchor><x>" + std::to_string(x) + "</x><y>" +
           std::to_string(y) + "</y><z>0</z></anchor></joint>\n";
  };
  world.insert(at, body("A", 0) + body("B", 1) + joint("AW", "A", "world", 0, 2) +
                       joint("BW", "B", "world", 1, 2) + joint("AB", "A", "B", 0.5, 1));
  std::ofstream(dir / "worlds/free_fall_thrown.xml") << world;
  return dir;
}

TEST(ValidateEngines, ExitsOneWhenOnlyOneEngineFails) {
  TempDir dir;
  const fs::path models = ModelsWithALoop(dir.path() / "models");
  std::string out, err;
  const int status = RunCli({"--only", "free_fall_thrown", "--engine", "both", "--params",
                             "/dev/null", "--models", models.string()},
                            &out, &err);
  EXPECT_EQ(status, 1) << out << err;
  EXPECT_EQ(LinesStartingWith(out, "free_fall_thrown     ode    largest horizontal error"), 1)
      << out;
  EXPECT_EQ(LinesStartingWith(out, "free_fall_thrown     mujoco ERROR: "), 1) << out;
  EXPECT_NE(out.find("closes a loop"), std::string::npos) << out;
  EXPECT_TRUE(HasTallies(out, {{1, 1, "ODE"}, {0, 1, "MuJoCo"}}))
      << out;
  // ODE alone, from the same files, passes.
  EXPECT_EQ(RunCli({"--only", "free_fall_thrown", "--params", "/dev/null", "--models",
                    models.string()},
                   &out, &err),
            0)
      << out << err;
}

TEST(ValidateEngines, ExitsOneWhenBothFail) {
  // The thrown body flies at 14 m/s: a 5 m/s explosion bound faults the
  // sim on either engine.
  std::string out, err;
  const int status = RunCli({"--only", "free_fall_thrown", "--engine", "both", "--params",
                             "/dev/null", "--maxLinearVelocity=5"},
                            &out, &err);
  EXPECT_EQ(status, 1) << out << err;
  EXPECT_EQ(LinesStartingWith(out, "free_fall_thrown     ode    ERROR: "), 1) << out;
  EXPECT_EQ(LinesStartingWith(out, "free_fall_thrown     mujoco ERROR: "), 1) << out;
  EXPECT_TRUE(HasTallies(out, {{0, 1, "ODE"}, {0, 1, "MuJoCo"}}))
      << out;
}

TEST(ValidateCommandLine, HelpListsTheFlags) {
  std::string out, err;
  ASSERT_EQ(RunCli({"--help"}, &out, &err), 0);
  for (const char* flag : {"--only", "--report", "--fast", "--list", "--models", "--engine"})
    EXPECT_NE(out.find(flag), std::string::npos) << flag;
}

}  // namespace
}  // namespace simpartner::validate
