// Batch files (batch/dtd/batch.dtd) and the plan of their runs: every
// refusal names the line and says why; runs are numbered in a fixed order
// and their controllers get their values.
#include <gtest/gtest.h>

#include <string>

#include "../support/programs.h"
#include "simpartner/batch/batch_file.h"
#include "simpartner/batch/plan.h"

namespace simpartner::batch {
namespace {

// A batch file in the source tree (so the shipped world is found), with
// `body` inside <batch>.
std::string File(const std::string& body) {
  return "<batch name=\"t\" version=\"1\">\n" + body + "</batch>\n";
}

const std::string kGood =
    "  <world>gen1_flat.xml</world>\n"                                      // line 2
    "  <parameter key=\"stepsize\">0.002</parameter>\n"                    // 3
    "  <duration>2</duration>\n"                                            // 4
    "  <controller>drive_to_point --lcm-url {url} --x {gx} --period {period}</controller>\n"  // 5
    "  <seeds>7 8</seeds>\n"                                                // 6
    "  <sweep>\n"                                                           // 7
    "    <vary key=\"contactMu\" values=\"0.5 1\"/>\n"                      // 8
    "    <vary name=\"gx\" values=\"2 3 4\"/>\n"                            // 9
    "    <vary name=\"period\" values=\"10\"/>\n"                           // 10
    "  </sweep>\n"
    "  <figure name=\"fx\" body=\"FrontChassis\" quantity=\"x\"/>\n";

std::string Name() { return test_support::SourceDir() + "/tests/batch/t.xml"; }

std::string Errors(const std::string& text) {
  const BatchParseResult r = ParseBatchFile(text, Name());
  EXPECT_FALSE(r.batch.has_value());
  return r.diagnostics.Format();
}

TEST(BatchFileTest, AGoodFileAndItsRuns) {
  const BatchParseResult r = ParseBatchFile(File(kGood), Name());
  ASSERT_TRUE(r.batch) << r.diagnostics.Format();
  const BatchFile& b = *r.batch;
  EXPECT_EQ(b.world, test_support::SourceDir() + "/models/worlds/gen1_flat.xml");
  EXPECT_EQ(b.duration, 2);
  ASSERT_EQ(b.sweep.size(), 3u);
  EXPECT_TRUE(b.sweep[0].is_parameter);
  EXPECT_FALSE(b.sweep[1].is_parameter);
  ASSERT_EQ(b.figures.size(), 1u);
  EXPECT_EQ(b.figures[0].quantity, Quantity::kX);

  // 2 x 3 x 1 combinations, each for 2 seeds: the last <vary> turns fastest.
  const std::vector<PlannedRun> runs = PlanRuns(b);
  ASSERT_EQ(runs.size(), 12u);
  EXPECT_EQ(RunTag(b, runs[0]), "batch=t run=0 contactMu=0.5 gx=2 period=10 seed=7");
  EXPECT_EQ(RunTag(b, runs[1]), "batch=t run=1 contactMu=0.5 gx=2 period=10 seed=8");
  EXPECT_EQ(RunTag(b, runs[2]), "batch=t run=2 contactMu=0.5 gx=3 period=10 seed=7");
  EXPECT_EQ(RunTag(b, runs[11]), "batch=t run=11 contactMu=1 gx=4 period=10 seed=8");
  // The sim gets the fixed parameters, then the swept ones.
  ASSERT_EQ(runs[11].parameters.size(), 2u);
  EXPECT_EQ(runs[11].parameters[1], (std::pair<std::string, std::string>{"contactMu", "1"}));
  EXPECT_EQ(ControllerArgv(b, runs[3], "udpm://x"),
            (std::vector<std::string>{"drive_to_point", "--lcm-url", "udpm://x", "--x", "3",
                                      "--period", "10"}));
}

TEST(BatchFileTest, ListModeTakesTheValuesTogether) {
  std::string text = kGood;
  text.replace(text.find("<sweep>"), 7, "<sweep mode=\"list\">");
  text.replace(text.find("values=\"0.5 1\""), 14, "values=\"0.5 1 2\"");
  text.replace(text.find("values=\"10\""), 11, "values=\"10 20 30\"");
  const BatchParseResult r = ParseBatchFile(File(text), Name());
  ASSERT_TRUE(r.batch) << r.diagnostics.Format();
  const std::vector<PlannedRun> runs = PlanRuns(*r.batch);
  ASSERT_EQ(runs.size(), 6u);  // 3 rows x 2 seeds
  EXPECT_EQ(RunTag(*r.batch, runs[4]), "batch=t run=4 contactMu=2 gx=4 period=30 seed=7");
}

TEST(BatchFileTest, RefusalsNameTheLineAndWhy) {
  auto with = [](const std::string& from, const std::string& to) {
    std::string text = kGood;
    text.replace(text.find(from), from.size(), to);
    return File(text);
  };
  const std::string f = Name() + ":";
  auto has = [](const std::string& errors, const std::string& part) {
    return errors.find(part) != std::string::npos;
  };
  std::string e = Errors(with("key=\"stepsize\"", "key=\"stepsise\""));
  EXPECT_TRUE(has(e, f + "3: parameter: unknown key 'stepsise' (did you mean 'stepsize'?)")) << e;
  e = Errors(with(">0.002<", ">5<"));
  EXPECT_TRUE(has(e, f + "3: parameter: value '5'")) << e;
  e = Errors(with("gen1_flat.xml", "nowhere.xml"));
  EXPECT_TRUE(has(e, f + "2: world: world 'nowhere.xml' not found")) << e;
  e = Errors(with("{url}", "udpm://239.255.76.67:7667"));
  EXPECT_TRUE(has(e, f + "5: controller: the controller is not told its bus")) << e;
  e = Errors(with("{period}", "{perod}"));
  EXPECT_TRUE(has(e, f + "5: controller: {perod} is neither url, seed, run, batch nor a variable"))
      << e;
  EXPECT_TRUE(has(e, f + "10: vary: variable 'period' is never used")) << e;
  e = Errors(with("key=\"contactMu\"", "key=\"contactMoo\""));
  EXPECT_TRUE(has(e, f + "8: vary: unknown key 'contactMoo' (did you mean 'contactMu'?)")) << e;
  e = Errors(with("<sweep>", "<sweep mode=\"list\">"));
  EXPECT_TRUE(has(e, "mode list: 'gx' has 3 values, 'contactMu' 2")) << e;
  e = Errors(with("7 8", "7 7"));
  EXPECT_TRUE(has(e, f + "6: seeds: seed 7 is given twice")) << e;
  e = Errors(with("key=\"stepsize\">0.002", "key=\"contactMu\">0.3"));
  EXPECT_TRUE(has(e, f + "8: vary: parameter 'contactMu' is fixed above and swept here")) << e;
  e = Errors(with("key=\"stepsize\">0.002", "key=\"lcmUrl\">udpm://x"));
  EXPECT_TRUE(has(e, f + "3: parameter: parameter 'lcmUrl' is the batch's to set")) << e;
  e = Errors(with("body=\"FrontChassis\"", "body=\"Nobody\""));
  EXPECT_TRUE(has(e, f + "12: figure: body 'Nobody' is in none of the world's robots")) << e;
  e = Errors(with("<duration>2</duration>", "<duraton>2</duraton>"));
  EXPECT_TRUE(has(e, f + "4:")) << e;  // the DTD: an element it does not know
  e = Errors(with("<duration>2<", "<duration>-1<"));
  EXPECT_TRUE(has(e, f + "4: duration: duration '-1': seconds of sim time above 0")) << e;
  e = Errors(with("drive_to_point", "no_such_controller_program"));
  EXPECT_TRUE(has(e, f + "5: controller: controller program 'no_such_controller_program' is "
                         "neither a program of this build or install nor on PATH"))
      << e;
  e = Errors(with("drive_to_point", "/nonexistent/controller"));
  EXPECT_TRUE(has(e, f + "5: controller: controller program '/nonexistent/controller' is not an "
                         "executable file"))
      << e;
}

// A batch is at most kMaxRuns runs: 100 x 101 values are refused with the
// sweep's line (a grid), 100 x 100 are taken.
TEST(BatchFileTest, TheNumberOfRunsIsBounded) {
  auto values = [](int n) {
    std::string text;
    for (int i = 0; i < n; ++i) text += (i ? " " : "") + std::to_string(i);
    return text;
  };
  auto sweep = [&](int a, int b) {
    return File("  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
                "  <controller>drive_to_point --lcm-url {url} --x {a} --z {b}</controller>\n"
                "  <sweep>\n    <vary name=\"a\" values=\"" + values(a) + "\"/>\n"
                "    <vary name=\"b\" values=\"" + values(b) + "\"/>\n  </sweep>\n");
  };
  const std::string e = Errors(sweep(100, 101));
  EXPECT_NE(e.find(Name() + ":5: sweep: the batch is 10100 runs (the seeds times the sweep's "
                            "combinations); at most 10000"),
            std::string::npos)
      << e;
  const BatchParseResult most = ParseBatchFile(sweep(100, 100), Name());
  ASSERT_TRUE(most.batch) << most.diagnostics.Format();
  EXPECT_EQ(PlanRuns(*most.batch).size(), 10000u);
}

// A controller's program is found as a shell finds it: here sh, on PATH
// only (a batch starts `python3 controller.py ...` so).
TEST(BatchFileTest, AControllerOnPathIsFound) {
  std::string text = kGood;
  text.replace(text.find("drive_to_point"), 14, "sh");
  const BatchParseResult r = ParseBatchFile(File(text), Name());
  EXPECT_TRUE(r.batch) << r.diagnostics.Format();
}

// A regression suite of scenarios: a world per run, a robot per run, each
// found before anything starts.
TEST(BatchFileTest, WorldsAndRobotsCanBeSwept) {
  const std::string scenarios =
      "  <world>gen1_flat.xml</world>\n  <duration>1</duration>\n"
      "  <controller>drive_to_point --lcm-url {url}</controller>\n"
      "  <sweep mode=\"list\">\n"
      "    <vary key=\"environment\" values=\"flat_ground.xml maze.xml\"/>\n"  // line 6
      "    <vary key=\"robot\" values=\"gen3 gen2\"/>\n"                       // line 7
      "  </sweep>\n";
  const BatchParseResult r = ParseBatchFile(File(scenarios), Name());
  ASSERT_TRUE(r.batch) << r.diagnostics.Format();
  const std::vector<PlannedRun> runs = PlanRuns(*r.batch);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].parameters[0].second, test_support::SourceDir() + "/models/worlds/maze.xml");
  EXPECT_EQ(runs[1].parameters[1], (std::pair<std::string, std::string>{"robot", "gen2"}));

  std::string bad = scenarios;
  bad.replace(bad.find("maze.xml"), 8, "maize.xml");
  bad.replace(bad.find("gen2"), 4, "gen5");
  const std::string e = Errors(File(bad));
  EXPECT_NE(e.find(Name() + ":6: vary: world 'maize.xml' not found"), std::string::npos) << e;
  EXPECT_NE(e.find(Name() + ":7: vary: "), std::string::npos) << e;
  EXPECT_NE(e.find("gen5"), std::string::npos) << e;
  std::string fixed = scenarios;
  fixed.replace(fixed.find("  <duration>"), 0, "  <parameter key=\"environment\">maze.xml</parameter>\n");
  EXPECT_NE(Errors(File(fixed)).find("the world is <world>'s"), std::string::npos);
}

TEST(BatchFileTest, AFileThatCannotBeReadSaysSo) {
  const BatchParseResult r = LoadBatchFile("/nonexistent/batch.xml");
  EXPECT_FALSE(r.batch);
  EXPECT_NE(r.diagnostics.Format().find("/nonexistent/batch.xml"), std::string::npos)
      << r.diagnostics.Format();
  const BatchParseResult fifo = LoadBatchFile("/dev/zero");
  EXPECT_FALSE(fifo.batch);  // not a regular file: refused without reading
}

}  // namespace
}  // namespace simpartner::batch
