// `simpartner-sim --check` as users run it: the real binary, its exit
// status, the summary on stdout and every problem on stderr as
// "file:line: element: message".
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/child_process.h"
#include "../support/programs.h"
#include "../support/text_file.h"

namespace simpartner::model {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = SP_SOURCE_DIR;

struct SimRun {
  int status = -1;  // exit status; 128 + signal if killed
  std::string out;
  std::string err;
};

using test_support::ReadText;

// Runs simpartner-sim with args, stdout and stderr to separate files of a
// directory of its own (a shell that redirects stderr and then becomes the
// sim); kills it if it takes longer than 30 s.
SimRun RunSim(const std::vector<std::string>& args) {
  SimRun run;
  char dir_template[] = "/tmp/sp_check_test.XXXXXX";
  const char* dir = mkdtemp(dir_template);
  if (dir == nullptr) {
    ADD_FAILURE() << "mkdtemp failed";
    return run;
  }
  const fs::path out = fs::path(dir) / "stdout", err = fs::path(dir) / "stderr";
  std::vector<std::string> argv = {"/bin/sh", "-c", "exec \"$@\" 2>'" + err.string() + "'", "sh",
                                   test_support::BuiltProgram("simpartner-sim")};
  argv.insert(argv.end(), args.begin(), args.end());
  {
    ChildProcess sim(argv, out.string());
    const std::optional<int> status = sim.Wait(std::chrono::seconds(30));
    if (!status) ADD_FAILURE() << "simpartner-sim --check did not finish in 30 s";
    run.status = status.value_or(-1);
  }  // killed and reaped here if it did not finish
  run.out = ReadText(out);
  run.err = ReadText(err);
  fs::remove_all(dir);
  return run;
}

std::vector<std::string> Check(const fs::path& world) {
  return {"--check", "--params", (kSource / "parameters.txt").string(),
          "--environment=" + world.string()};
}

bool HasLine(const std::string& text, const std::string& line) {
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

TEST(CheckProcess, BrokenWorldExitsNonZeroWithFileLineElementMessage) {
  const fs::path world = kSource / "tests/models/broken/physics_zero_mass.xml";
  const SimRun run = RunSim(Check(world));
  EXPECT_NE(run.status, 0);
  EXPECT_TRUE(HasLine(run.err, world.string() +
                                   ":6: mass: object 'Crate': mass must be positive, got 0"))
      << "stderr:\n" << run.err;
  EXPECT_EQ(run.out.find("objects:"), std::string::npos) << "no summary for a broken world";
}

TEST(CheckProcess, BrokenRobotIsReportedInBothFiles) {
  const fs::path world = kSource / "tests/models/broken/robot_joint_missing_body.xml";
  const fs::path robot = kSource / "tests/models/broken/robots/joint_missing_body.xml";
  const SimRun run = RunSim(Check(world));
  EXPECT_NE(run.status, 0);
  EXPECT_TRUE(HasLine(run.err,
                      world.string() + ":6: robot: robot 'TwoLink': cannot load "
                                       "'robots/joint_missing_body.xml' (1 problem)"))
      << "stderr:\n" << run.err;
  EXPECT_TRUE(HasLine(run.err, robot.string() + ":25: body2: joint 'Axle': body2 'Wheels' is "
                                                "not a body of robot 'TwoLink'"))
      << "stderr:\n" << run.err;
}

// A field sensor's parameter out of range stops --check at its line.
TEST(CheckProcess, BadSensorParameterIsRefusedAtItsLine) {
  const fs::path world = kSource / "tests/models/broken/robot_imu_negative_noise.xml";
  const fs::path robot = kSource / "tests/models/broken/robots/imu_negative_noise.xml";
  const SimRun run = RunSim(Check(world));
  EXPECT_EQ(run.status, 2) << "stderr:\n" << run.err;
  EXPECT_TRUE(HasLine(run.err, robot.string() + ":32: parameter: sensor 'Imu': gyroNoiseDensity "
                                                "-0.001 rad/s/sqrt(Hz) is out of range [0, 10]"))
      << "stderr:\n" << run.err;
}

TEST(CheckProcess, GoodWorldExitsZeroWithTheSummary) {
  const fs::path world = kSource / "models/worlds/flat_ground.xml";
  const SimRun run = RunSim(Check(world));
  EXPECT_EQ(run.status, 0) << "stderr:\n" << run.err;
  EXPECT_EQ(run.err, "");
  // flat_ground places WorkPartner gen3: 202 kg (SPEC 7).
  EXPECT_NE(run.out.find("robot 'WorkPartner' = WorkPartner gen3"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("total mass: 202.000 kg"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("bodies: "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("actuators: "), std::string::npos) << run.out;
}

// What scripts use to learn a setting (scripts/run: log, dbserver): the
// file's values with the command line's overrides applied, validated.
TEST(CheckProcess, PrintParametersShowsTheFileWithTheOverrides) {
  const SimRun run = RunSim({"--print-parameters", "--params", (kSource / "parameters.txt").string(),
                             "--stepsize=0.002", "--log=0"});
  EXPECT_EQ(run.status, 0) << "stderr:\n" << run.err;
  EXPECT_TRUE(HasLine(run.out, "stepsize=0.002")) << run.out;
  EXPECT_TRUE(HasLine(run.out, "log=0")) << run.out;
  EXPECT_TRUE(HasLine(run.out, "dbname=simpartner")) << run.out;  // from the file
  EXPECT_EQ(run.out.find("objects:"), std::string::npos) << "nothing loaded, nothing started";

  const SimRun bad = RunSim({"--print-parameters", "--params", (kSource / "parameters.txt").string(),
                             "--stepsize=2"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("command line: stepsize: value '2' is out of range"), std::string::npos)
      << bad.err;
  EXPECT_EQ(bad.out, "");
}

// Values that --check once passed and that then made ODE
// abort the sim. Each is refused by --check itself (exit 2) with the
// diagnostic at its line naming the allowed range.
struct CheckRangeCase {
  const char* name;
  std::string object;      // the <object>'s inner elements, one per line after line 3
  std::string diagnostic;  // after "<file>:"
};

std::string Transformation(const std::string& x, const std::string& y) {
  return "<transformation><T00>1</T00><T01>0</T01><T02>0</T02><T03>" + x +
         "</T03><T10>0</T10><T11>1</T11><T12>0</T12><T13>" + y +
         "</T13><T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23></transformation>";
}

TEST(CheckProcess, ValuesThatAbortedOdeAreRefusedWithTheirRange) {
  const std::string box = "<size><x>1</x><y>1</y><z>1</z></size>";
  const std::string at_rest = Transformation("0", "0.5");
  const std::vector<CheckRangeCase> cases = {
      {"mass 1e308 kg", "<mass>1e308</mass>\n" + box + "\n" + at_rest,
       "4: mass: object 'Thing': mass 1e+308 kg is out of range [0.0001, 1000000] kg"},
      {"mass 4.9e-324 kg", "<mass>4.9e-324</mass>\n" + box + "\n" + at_rest,
       "4: mass: object 'Thing': mass 4.940656458e-324 kg is out of range [0.0001, 1000000] kg"},
      {"mass 1e-12 kg", "<mass>1e-12</mass>\n" + box + "\n" + at_rest,
       "4: mass: object 'Thing': mass 1e-12 kg is out of range [0.0001, 1000000] kg"},
      {"size 1e-310 m", "<mass>1</mass>\n<size><x>1e-310</x><y>1</y><z>1</z></size>\n" + at_rest,
       "5: size: object 'Thing': size x 1e-310 m is out of range [0.001, 10000] m"},
      {"size 1e100 m", "<mass>1</mass>\n<size><x>1</x><y>1e100</y><z>1</z></size>\n" + at_rest,
       "5: size: object 'Thing': size y 1e+100 m is out of range [0.001, 10000] m"},
      {"placed 1e10 m away", "<mass>1</mass>\n" + box + "\n" + Transformation("1e10", "0.5"),
       "6: transformation: object 'Thing': position (1e+10, 0.5, 0) m is out of range: |x|, "
       "|y|, |z| <= 1000000 m"},
      {"velocity 1e308 m/s",
       "<mass>1</mass>\n" + box + "\n" + at_rest +
           "\n<translationalVelocity><vx>1e308</vx><vy>0</vy><vz>0</vz></translationalVelocity>",
       "7: translationalVelocity: object 'Thing': translationalVelocity (1e+308, 0, 0) m/s is out "
       "of range: speed at most 10000 m/s"},
  };
  char dir_template[] = "/tmp/sp_check_ranges.XXXXXX";
  const char* dir = mkdtemp(dir_template);
  ASSERT_NE(dir, nullptr);
  for (const CheckRangeCase& c : cases) {
    const fs::path world = fs::path(dir) / "world.xml";
    std::ofstream(world) << "<world name=\"W\">\n<surface><a>0</a><b>1</b><c>0</c><d>0</d></surface>\n"
                            "<object type=\"Box\" name=\"Thing\">\n"
                         << c.object << "\n</object>\n</world>\n";
    const SimRun run = RunSim(Check(world));
    EXPECT_EQ(run.status, 2) << c.name << ": stderr:\n" << run.err;
    EXPECT_TRUE(HasLine(run.err, world.string() + ":" + c.diagnostic))
        << c.name << ": stderr:\n" << run.err;
  }
  // The shipped gen1 robot placed 1e10 m away: refused at the placement.
  const fs::path world = fs::path(dir) / "far_robot.xml";
  std::ofstream(world) << "<world name=\"W\">\n<robot name=\"WorkPartner\" file=\""
                       << (kSource / "models/robots/workpartner_gen1.xml").string() << "\">\n"
                       << Transformation("1e10", "0") << "\n</robot>\n</world>\n";
  const SimRun run = RunSim(Check(world));
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_TRUE(HasLine(run.err, world.string() +
                                   ":3: transformation: robot 'WorkPartner': placed at (1e+10, 0, "
                                   "0) m, its body 'FrontChassis' is at (1e+10, 0.715, 0) m, out "
                                   "of range: |x|, |y|, |z| <= 1000000 m"))
      << run.err;
  fs::remove_all(dir);
}

// A device or a FIFO as the world: refused at once (before: /dev/zero was
// read until allocation failed, a FIFO blocked --check forever).
TEST(CheckProcess, DeviceOrFifoWorldIsRefusedAtOnce) {
  const SimRun zero = RunSim(Check("/dev/zero"));
  EXPECT_EQ(zero.status, 2);
  EXPECT_TRUE(HasLine(zero.err, "/dev/zero: not a regular file (character device); model files "
                                "must be regular files"))
      << zero.err;
  char dir_template[] = "/tmp/sp_check_fifo.XXXXXX";
  const char* dir = mkdtemp(dir_template);
  ASSERT_NE(dir, nullptr);
  const fs::path fifo = fs::path(dir) / "world.xml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const SimRun run = RunSim(Check(fifo));  // RunSim fails the test after 30 s
  EXPECT_EQ(run.status, 2);
  EXPECT_TRUE(HasLine(run.err, fifo.string() + ": not a regular file (FIFO); model files must "
                                               "be regular files"))
      << run.err;
  fs::remove_all(dir);
}

// A heightfield of 1100 x 1100 samples makes a SIM_MODEL of 4.8 MB, more
// than a receiver's 4 MiB socket buffer takes: --check says so with the
// size (before, it passed, and each SIM_MODEL_REQUEST returned the whole
// model). 1000 x 1000 (4.0 MB) still passes.
TEST(CheckProcess, AModelTooLargeForTheBusIsRefusedWithItsSize) {
  char dir_template[] = "/tmp/sp_check_big.XXXXXX";
  const char* dir = mkdtemp(dir_template);
  ASSERT_NE(dir, nullptr);
  auto world = [&](int n) {
    const fs::path path = fs::path(dir) / ("field" + std::to_string(n) + ".xml");
    std::ofstream out(path);
    out << "<world name=\"Field\" version=\"1\">\n<gravity><x>0</x><y>-9.81</y><z>0</z>"
           "</gravity>\n<heightfield rows=\"" << n << "\" columns=\"" << n << "\">\n"
        << "<width>100</width><depth>100</depth><samples>";
    for (int i = 0; i < n * n; ++i) out << "0 ";
    out << "</samples></heightfield>\n</world>\n";
    return path;
  };
  const SimRun big = RunSim(Check(world(1100)));
  EXPECT_EQ(big.status, 2) << big.out << big.err;
  // About 4.8 MB: 1,100 x 1,100 heights and the model's other fields.
  EXPECT_NE(big.err.find("SIM_MODEL would be 484"), std::string::npos) << big.err;
  EXPECT_NE(big.err.find("more than the 4 MiB a receiver's socket buffer takes"),
            std::string::npos)
      << big.err;
  const SimRun fits = RunSim(Check(world(1000)));
  EXPECT_EQ(fits.status, 0) << fits.err;
  fs::remove_all(dir);
}

// --robot: the summary names the chosen robot in place of the world's; a
// wrong name stops before anything with a did-you-mean.
TEST(CheckProcess, RobotFlagPutsTheNamedRobotIntoTheWorld) {
  std::vector<std::string> args = Check(kSource / "models/worlds/maze.xml");
  args.insert(args.end(), {"--robot", "gen4", "--robot-pose", "1,0,2,90"});
  const SimRun run = RunSim(args);
  EXPECT_EQ(run.status, 0) << run.err;
  // The file as found: relative to the working directory when it is there
  // (run by hand from the source tree), else under the data roots.
  const std::string named = "  robot 'WorkPartner' = WorkPartner gen4 (";
  std::istringstream lines(run.out);
  std::string found;
  for (std::string l; std::getline(lines, l);)
    if (l.rfind(named, 0) == 0 && l.back() == ')')
      found = l.substr(named.size(), l.size() - named.size() - 1);
  ASSERT_FALSE(found.empty()) << run.out;
  EXPECT_TRUE(fs::equivalent(found, kSource / "models/robots/workpartner_gen4.xml")) << found;
  EXPECT_EQ(run.out.find("gen3"), std::string::npos) << run.out;

  args = Check(kSource / "models/worlds/maze.xml");
  args.insert(args.end(), {"--robot=gen4-light"});
  const SimRun wrong = RunSim(args);
  EXPECT_EQ(wrong.status, 2);
  EXPECT_TRUE(HasLine(wrong.err, "command line: --robot: unknown robot 'gen4-light' (did you mean "
                                 "'gen1-light'?); give one of gen1, gen1-light, gen2, gen3, gen4 "
                                 "or a robot file"))
      << wrong.err;
}

}  // namespace
}  // namespace simpartner::model
