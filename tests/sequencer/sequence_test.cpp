// The sequence format: both versions read into the timeline the player
// sends, the malformed corpus refused with file:line: messages, the shipped
// sequences valid against their worlds, and --check as a function.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "simpartner/command_t.hpp"
#include "simpartner/model/loader.h"
#include "simpartner/sequencer/check.h"
#include "simpartner/sequencer/cli.h"
#include "simpartner/sequencer/sequence.h"

namespace simpartner::sequencer {
namespace {

namespace fs = std::filesystem;

const std::string kSource = SP_SOURCE_DIR;
const std::string kGen3World = kSource + "/models/worlds/flat_ground.xml";

Sequence Parse(const std::string& xml) {
  SequenceParseResult r = ParseSequence(xml, "test.xml");
  EXPECT_TRUE(r.sequence.has_value()) << r.diagnostics.Format();
  return r.sequence ? *r.sequence : Sequence{};
}

std::string FirstProblem(const std::string& xml) {
  SequenceParseResult r = ParseSequence(xml, "test.xml");
  EXPECT_FALSE(r.sequence.has_value());
  return r.diagnostics.empty() ? "" : r.diagnostics.items().front().Format();
}

TEST(SequenceFormat, VersionOneIsTheOriginalListWithPausesOnPortZero) {
  const Sequence s = Parse(R"(<?xml version="1.0"?>
<sequence version="1">
  <command>
    <commandString>1000,1000,100,0,0,0.2</commandString>
    <port>1028</port>
  </command>
  <command><commandString>2</commandString><port>0</port></command>
  <command><port>1029</port><commandString>1000,1000,100,0,0,0</commandString></command>
  <command><commandString>0.5</commandString><port>0</port></command>
</sequence>)");
  EXPECT_EQ(s.version, 1);
  ASSERT_EQ(s.segments.size(), 1u);
  const Segment& seg = s.segments[0];
  ASSERT_EQ(seg.commands.size(), 2u);  // the pauses are the sequencer's own
  EXPECT_EQ(seg.commands[0].port, 1028);
  EXPECT_EQ(seg.commands[0].line, 3);
  EXPECT_EQ(seg.commands[0].text, "1000,1000,100,0,0,0.2");
  EXPECT_DOUBLE_EQ(seg.commands[0].time, 0.0);
  EXPECT_EQ(seg.commands[0].action, kOriginal);
  EXPECT_EQ(seg.commands[1].port, 1029);
  EXPECT_EQ(seg.commands[1].line, 8);
  EXPECT_DOUBLE_EQ(seg.commands[1].time, 2.0);
  EXPECT_DOUBLE_EQ(seg.end, 2.5);  // the last pause lasts too
  EXPECT_FALSE(seg.wait.has_value());
}

TEST(SequenceFormat, VersionOneRepeatPlaysItsCommandsCountTimes) {
  const Sequence s = Parse(R"(<sequence version="1">
  <repeat count="3">
    <command><commandString>1000,1000,100,0,0,1</commandString><port>1028</port></command>
    <command><commandString>1</commandString><port>0</port></command>
    <command><commandString>1000,1000,100,0,0,0</commandString><port>1028</port></command>
    <command><commandString>0.5</commandString><port>0</port></command>
  </repeat>
</sequence>)");
  const std::vector<Command>& c = s.segments[0].commands;
  ASSERT_EQ(c.size(), 6u);
  const double times[6] = {0.0, 1.0, 1.5, 2.5, 3.0, 4.0};
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_DOUBLE_EQ(c[k].time, times[k]) << k;
    EXPECT_EQ(c[k].line, k % 2 == 0 ? 3 : 5) << k;
  }
  EXPECT_DOUBLE_EQ(s.segments[0].end, 4.5);
}

TEST(SequenceFormat, BareCommandListIsReadAsVersionOneWithANote) {
  SequenceParseResult r = ParseSequence(R"(<?xml version="1.0"?>
<!-- as the original wrote them -->
<command>
  <commandString>1000,1000,100,0,0,0.2</commandString>
  <port>1028</port>
</command>
<command><commandString>1000,1000,100,0,0,0</commandString><port>1029</port></command>
)", "bare.xml");
  ASSERT_TRUE(r.sequence.has_value()) << r.diagnostics.Format();
  EXPECT_TRUE(r.sequence->rootless);
  EXPECT_EQ(r.sequence->version, 1);
  ASSERT_EQ(r.sequence->segments[0].commands.size(), 2u);
  EXPECT_EQ(r.sequence->segments[0].commands[0].line, 3);  // lines are the file's
  EXPECT_EQ(r.sequence->segments[0].commands[1].line, 7);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("add <sequence version=\"1\">"), std::string::npos) << r.notes[0];
}

TEST(SequenceFormat, VersionTwoTimesRampsRepeatsWaitsAndComments) {
  const Sequence s = Parse(R"(<sequence version="2" robot="WorkPartner">
  <comment>start</comment>
  <set target="TurnerMotor" at="0.5">1000,0.2,100,100,0</set>
  <set target="Axle1Motor">1000,1</set>
  <pause seconds="1"/>
  <hold port="1028"/>
  <wait joint="Turner" angle="0.2" tolerance="0.001" timeout="5"/>
  <repeat count="2" period="3">
    <set target="Axle2Motor" at="1">1000,1</set>
  </repeat>
  <ramp target="Axle3Motor" from="1000,0" to="1000,1" duration="0.4" every="0.1"/>
  <read target="Scanner" at="10"/>
</sequence>)");
  EXPECT_EQ(s.version, 2);
  EXPECT_EQ(s.robot, "WorkPartner");
  ASSERT_EQ(s.segments.size(), 2u);
  const Segment& a = s.segments[0];
  ASSERT_EQ(a.commands.size(), 3u);
  EXPECT_EQ(a.commands[0].target, "TurnerMotor");
  EXPECT_DOUBLE_EQ(a.commands[0].time, 0.5);
  EXPECT_EQ(a.commands[1].target, "Axle1Motor");
  EXPECT_DOUBLE_EQ(a.commands[1].time, 0.5);  // follows the one before
  EXPECT_EQ(a.commands[2].port, 1028);
  EXPECT_EQ(a.commands[2].action, command_t::ACTION_HOLD);
  EXPECT_DOUBLE_EQ(a.commands[2].time, 1.5);
  ASSERT_TRUE(a.wait.has_value());
  EXPECT_EQ(a.wait->kind, Wait::Kind::kJoint);
  EXPECT_DOUBLE_EQ(a.wait->start, 1.5);
  EXPECT_DOUBLE_EQ(a.wait->timeout, 5.0);
  EXPECT_EQ(a.wait->line, 7);
  ASSERT_EQ(a.notes.size(), 1u);
  EXPECT_EQ(a.notes[0].text, "start");
  // After the wait the times count from when it was met.
  const Segment& b = s.segments[1];
  ASSERT_EQ(b.commands.size(), 2u + 5u + 1u);
  EXPECT_DOUBLE_EQ(b.commands[0].time, 1.0);  // pass 1 starts at 0
  EXPECT_DOUBLE_EQ(b.commands[1].time, 4.0);  // pass 2 starts at 3
  // The ramp starts where the repeat ended (2 x 3 s): 5 sets, 0.1 s apart.
  for (int k = 0; k < 5; ++k) {
    EXPECT_DOUBLE_EQ(b.commands[2 + k].time, 6.0 + 0.1 * k) << k;
    EXPECT_EQ(b.commands[2 + k].target, "Axle3Motor");
  }
  EXPECT_EQ(b.commands[2].text, "1000,0");
  EXPECT_EQ(b.commands[4].text, "1000,0.5");
  EXPECT_EQ(b.commands[6].text, "1000,1");
  EXPECT_EQ(b.commands[7].action, command_t::ACTION_READ);
  EXPECT_DOUBLE_EQ(b.commands[7].time, 10.0);
  EXPECT_DOUBLE_EQ(b.end, 10.0);
}

TEST(SequenceFormat, WaitsOnTimeAndSensors) {
  const Sequence s = Parse(R"(<sequence version="2">
  <wait time="12.5"/>
  <wait sensor="Scanner" index="5" below="1.0" timeout="30"/>
  <wait sensor="Position" index="0" above="2" timeout="30"/>
</sequence>)");
  ASSERT_EQ(s.segments.size(), 4u);
  EXPECT_EQ(s.segments[0].wait->kind, Wait::Kind::kTime);
  EXPECT_DOUBLE_EQ(s.segments[0].wait->sim_time, 12.5);
  EXPECT_EQ(s.segments[1].wait->kind, Wait::Kind::kSensor);
  EXPECT_EQ(s.segments[1].wait->index, 5);
  EXPECT_FALSE(s.segments[1].wait->above);
  EXPECT_DOUBLE_EQ(s.segments[1].wait->threshold, 1.0);
  EXPECT_TRUE(s.segments[2].wait->above);
  EXPECT_FALSE(s.segments[3].wait.has_value());
}

TEST(SequenceFormat, UnrollingIsBounded) {
  const std::string problem = FirstProblem(R"(<sequence version="2">
  <repeat count="1000">
    <repeat count="1000">
      <set target="Axle1Motor">1000,1</set>
    </repeat>
  </repeat>
</sequence>)");
  EXPECT_NE(problem.find("test.xml:4: set: the sequence unrolls to more than 250000 commands"),
            std::string::npos)
      << problem;
  const std::string ramp = FirstProblem(R"(<sequence version="2">
  <ramp target="A" from="0" to="1" duration="1000" every="0.000001"/>
</sequence>)");
  EXPECT_NE(ramp.find("test.xml:2: ramp: the sequence unrolls to more than"), std::string::npos)
      << ramp;
}

// The DOCTYPE policy every XML file has (common/.../xml_document.h): one
// that names the sequence's own DTD, or nothing, is fine.
TEST(SequenceFormat, DoctypeMayNameTheVersionsDtdOnly) {
  for (const char* doctype : {"<!DOCTYPE sequence>", "<!DOCTYPE sequence SYSTEM \"sequence_v2.dtd\">"}) {
    const Sequence s = Parse(std::string("<?xml version=\"1.0\"?>\n") + doctype +
                             "\n<sequence version=\"2\"><pause seconds=\"1\"/></sequence>");
    EXPECT_EQ(s.version, 2) << doctype;
  }
  EXPECT_NE(FirstProblem("<?xml version=\"1.0\"?>\n<!DOCTYPE sequence SYSTEM \"sequence_v1.dtd\">\n"
                         "<sequence version=\"2\"/>")
                .find("test.xml:2: DOCTYPE: the DOCTYPE names 'sequence_v1.dtd'; the file is "
                      "validated against the built-in sequence_v2.dtd"),
            std::string::npos);
}

TEST(SequenceFormat, RootMayNameItsWorld) {
  const Sequence s = Parse(R"(<sequence version="2" world=" pole_task.xml "><pause seconds="1"/></sequence>)");
  EXPECT_EQ(s.world, "pole_task.xml");
  EXPECT_EQ(Parse(R"(<sequence version="2"/>)").world, "");
  EXPECT_EQ(FirstProblem("<sequence version=\"2\" world=\"  \"/>"),
            "test.xml:1: sequence: world is empty: give the world file the sequence is made for, "
            "e.g. world=\"pole_task.xml\", or leave the attribute out");
  for (const char* bad : {"pole_task", "worlds/", ".xml", "worlds/.xml"}) {
    EXPECT_EQ(FirstProblem(std::string("<sequence version=\"2\" world=\"") + bad + "\"/>"),
              std::string("test.xml:1: sequence: world '") + bad +
                  "' is not a world file name (NAME.xml, e.g. pole_task.xml)");
  }
  // Version 1 is the original's format: it has no world.
  EXPECT_NE(FirstProblem(R"(<sequence version="1" world="pole_task.xml"/>)")
                .find("No declaration for attribute world"),
            std::string::npos);
}

TEST(SequenceFormat, DtdsAreBuiltIn) {
  EXPECT_NE(SequenceDtd(1).find("<!ELEMENT commandString"), std::string::npos);
  EXPECT_EQ(SequenceDtd(1).find("<!ELEMENT wait"), std::string::npos);
  EXPECT_NE(SequenceDtd(2).find("<!ELEMENT wait"), std::string::npos);
}

// Every file of tests/sequencer/malformed with the first message it must
// give (checked against gen3 on flat ground).
const std::map<std::string, std::string>& Expected() {
  static const std::map<std::string, std::string> expected = {
      {"doctype.xml", "doctype.xml:2: DOCTYPE: declarations inside the file are not allowed"},
      {"no_version.xml",
       "no_version.xml:2: sequence: no version attribute: add version=\"1\" (the original's "
       "<command>/<port> format) or version=\"2\""},
      {"not_well_formed.xml",
       "not_well_formed.xml:6: Opening and ending tag mismatch: commandString line 4 and command"},
      {"unknown_version.xml", "unknown_version.xml:3: sequence: version '3' is not known (1 or 2)"},
      {"wrong_root.xml",
       "wrong_root.xml:2: commands: the root element must be <sequence version=\"1\">"},
      {"v1_bad_number.xml", "v1_bad_number.xml:3: command: Axle1Motor: values[5] = 'fast'"},
      {"v1_low_port.xml", "v1_low_port.xml:3: port: port 80 is not a legacy port"},
      {"v1_missing_port.xml",
       "v1_missing_port.xml:4: command: Element command content does not follow the DTD"},
      {"v1_negative_pause.xml",
       "v1_negative_pause.xml:5: commandString: negative pause -2 s on port 0 (the sequencer)"},
      {"v1_unknown_port.xml",
       "v1_unknown_port.xml:5: command: port 1099 is not an actuator or sensor of the model"},
      {"v1_v2_element.xml",
       "v1_v2_element.xml:2: sequence: Element sequence content does not follow the DTD"},
      {"v1_wrong_count.xml",
       "v1_wrong_count.xml:3: command: Axle1Motor: set values = '1000,1000,100,0,0': velocity "
       "controller 'Axle1Motor': expected 6 or 2 values"},
      {"v2_actuator_wait.xml",
       "v2_actuator_wait.xml:3: wait: 'Axle1Motor' is an actuator (velocity controller), not a "
       "sensor"},
      {"v2_angle_wrong_count.xml",
       "v2_angle_wrong_count.xml:4: set: TurnerMotor: set values = '1000,1000,100,0,0,0.2"},
      {"v2_negative_at.xml", "v2_negative_at.xml:3: set: at -1 is negative"},
      {"v2_negative_pause.xml", "v2_negative_pause.xml:4: pause: seconds -1 is negative"},
      {"v2_port_zero_set.xml", "v2_port_zero_set.xml:3: set: port 0 is the sequencer itself"},
      {"v2_ramp_mismatch.xml",
       "v2_ramp_mismatch.xml:3: ramp: from has 2 values and to has 3; they must match"},
      {"v2_read_actuator.xml",
       "v2_read_actuator.xml:3: read: Axle1Motor: read values = '': velocity controller "
       "'Axle1Motor': action 'read' does not apply to an actuator"},
      {"v2_repeat_count.xml",
       "v2_repeat_count.xml:3: repeat: count 2.5 must be a whole number"},
      {"v2_scanner_index.xml",
       "v2_scanner_index.xml:4: wait: sensor 'Scanner' (scanner) reads 11 values; index 11 does "
       "not exist"},
      {"v2_target_and_port.xml",
       "v2_target_and_port.xml:4: set: both target 'Axle1Motor' and port 1028 are given; use one"},
      {"v2_unknown_name.xml",
       "v2_unknown_name.xml:4: set: 'Axel2Motor' is not an actuator or sensor of the model; did "
       "you mean 'Axle2Motor'"},
      {"v2_unknown_robot.xml",
       "v2_unknown_robot.xml:3: set: robot 'WorkPartner2' of 'WorkPartner2/Axle1Motor' is not in "
       "the model; did you mean 'WorkPartner'?"},
      {"v2_sequence_robot.xml",
       "v2_sequence_robot.xml:3: sequence: robot 'WorkPartner3' is not in the model (it has "
       "'WorkPartner')"},
      {"v2_wait_index_huge.xml",
       "v2_wait_index_huge.xml:4: wait: index 1e+11 must be a whole number from 0 to 100000"},
      {"v2_wait_no_timeout.xml",
       "v2_wait_no_timeout.xml:4: wait: timeout is missing"},
      {"v2_wait_unknown_joint.xml",
       "v2_wait_unknown_joint.xml:4: wait: 'Turnr' is not a joint of the model; did you mean "
       "'Turner'?"},
  };
  return expected;
}

TEST(SequenceMalformedCorpus, EveryFileIsRefusedWithItsFileLineAndMessage) {
  const fs::path dir = kSource + "/tests/sequencer/malformed";
  std::set<std::string> seen;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".xml") continue;
    const std::string name = entry.path().filename().string();
    seen.insert(name);
    const auto it = Expected().find(name);
    ASSERT_NE(it, Expected().end()) << name << " has no expected message in this test";
    // Run from the corpus directory so the file name in messages is short.
    const fs::path previous = fs::current_path();
    fs::current_path(dir);
    std::ostringstream out, err;
    const int status = RunSequencer({"--check", name, "--environment", kGen3World}, out, err);
    fs::current_path(previous);
    EXPECT_EQ(status, 2) << name << "\n" << out.str() << err.str();
    EXPECT_EQ(out.str(), "") << name;
    // The first line that names the file is the expected message.
    std::istringstream lines(err.str());
    std::string line, first;
    while (std::getline(lines, line)) {
      if (line.rfind(name + ":", 0) == 0) {
        first = line;
        break;
      }
    }
    EXPECT_EQ(first.substr(0, it->second.size()), it->second) << name << "\n" << err.str();
  }
  EXPECT_GE(seen.size(), 15u);
  EXPECT_EQ(seen.size(), Expected().size()) << "an expected message without its file";
}

// Each shipped sequence with the world it was written for.
TEST(SequenceShipped, EveryFileChecksAgainstItsWorld) {
  const std::map<std::string, std::string> worlds = {
      {"gen1_circle_equal_speeds.xml", "gen1_flat.xml"},
      {"gen1_circle_differential.xml", "gen1_flat.xml"},
      {"gen1_circle_matched.xml", "gen1_flat.xml"},
      {"gen1_light_skid.xml", "slippery_ground.xml"},
      {"gen2_scanner_sweep.xml", "scanner_wall.xml"},
      {"gen3_pole_task.xml", "pole_task.xml"},
      {"gen4_test_track.xml", "test_track.xml"},
      {"gen1_light_caterpillar.xml", "slippery_ground.xml"},
      {"gen1_light_rolking.xml", "slippery_ground.xml"},
      {"gen3_soil_drive.xml", "sand_field.xml"},
      {"gen3_snow_drive.xml", "snow_field.xml"},
      {"gen3_hills_drive.xml", "sand_hills.xml"},
      {"sensor_rig_spin.xml", "sensor_rig.xml"},
  };
  size_t checked = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(kSource + "/sequences")) {
    if (entry.path().extension() != ".xml") continue;
    const std::string name = entry.path().filename().string();
    const auto it = worlds.find(name);
    ASSERT_NE(it, worlds.end()) << name << ": which world is it for?";
    // The file names it, and --check alone uses it.
    const SequenceParseResult parsed = LoadSequenceFile(entry.path().string());
    ASSERT_TRUE(parsed.sequence) << parsed.diagnostics.Format();
    EXPECT_EQ(parsed.sequence->world, it->second) << name;
    std::ostringstream named_out, named_err;
    EXPECT_EQ(RunSequencer({"--check", entry.path().string()}, named_out, named_err), 0)
        << name << "\n" << named_err.str();
    EXPECT_NE(named_out.str().find("models/worlds/" + it->second +
                                   "' (the world the sequence names)"),
              std::string::npos)
        << named_out.str();
    std::ostringstream out, err;
    const int status = RunSequencer({"--check", entry.path().string(), "--environment",
                                     kSource + "/models/worlds/" + it->second},
                                    out, err);
    EXPECT_EQ(status, 0) << name << "\n" << err.str();
    ++checked;
  }
  EXPECT_GE(checked, 6u);
}

// The pole task as written: the validation's timeline (experiments_robot.cpp).
TEST(SequenceShipped, PoleTaskKeepsTheValidationsTimes) {
  const SequenceParseResult r = LoadSequenceFile(kSource + "/sequences/gen3_pole_task.xml");
  ASSERT_TRUE(r.sequence) << r.diagnostics.Format();
  const Segment& s = r.sequence->segments.at(0);
  // 3 drives x (50 ramp-up + 50 ramp-down) x 4 wheels, 4 claw and 2 elbow
  // moves on both arms.
  EXPECT_EQ(s.commands.size(), 3u * 100u * 4u + 6u * 2u);
  EXPECT_EQ(s.commands.front().target, "Axle1Motor");
  EXPECT_DOUBLE_EQ(s.commands.front().time, 0.5);
  // Drive 0.1 m at 0.5 rad/s: cruise 0.1 / (0.5 * 0.235) - 0.5 s, then
  // +0.3 s the claws close.
  const double cruise = 0.1 / (0.5 * 0.235) - 0.5;
  const double claws = 0.5 + 2 * 0.5 + cruise + 0.3;
  bool found = false;
  for (const Command& c : s.commands) {
    if (c.target == "RightGripUpperMotor") {
      EXPECT_NEAR(c.time, claws, 1e-12);
      EXPECT_EQ(c.text, "10.0,-0.3,2.0,0.0,0.0");
      found = true;
      break;
    }
  }
  EXPECT_TRUE(found);
}

TEST(SequenceOfflineCheck, WithoutAWorldOnlyTheFormIsChecked) {
  std::ostringstream out, err;
  EXPECT_EQ(RunSequencer({"--check", kSource + "/tests/sequencer/malformed/v2_unknown_name.xml"},
                         out, err),
            0)
      << err.str();
  EXPECT_NE(out.str().find("names and ports not checked"), std::string::npos) << out.str();
}

TEST(SequenceOfflineCheck, AnotherWorldThanTheNamedOneIsRefused) {
  const std::string sequence = kSource + "/sequences/gen3_pole_task.xml";
  const std::string pole_task = kSource + "/models/worlds/pole_task.xml";
  std::ostringstream out, err;
  EXPECT_EQ(RunSequencer({"--check", sequence, "--environment", kGen3World}, out, err), 2);
  EXPECT_NE(err.str().find(sequence + ":3: sequence: the sequence is made for world "
                                      "'pole_task.xml' ("),
            std::string::npos)
      << err.str();
  EXPECT_NE(err.str().find("pole_task.xml), not for '" + kGen3World + "'"), std::string::npos)
      << err.str();
  // The same world, however it is spelled, is fine.
  std::ostringstream same_out, same_err;
  EXPECT_EQ(RunSequencer({"--check", sequence, "--environment",
                          kSource + "/models/../models/worlds/pole_task.xml"},
                         same_out, same_err),
            0)
      << same_err.str();
  EXPECT_EQ(same_out.str().find("(the world the sequence names)"), std::string::npos);
}

TEST(SequenceOfflineCheck, NamedWorldIsLookedForNextToTheSequenceFirst) {
  const fs::path dir = fs::temp_directory_path() / ("sp_seq_world_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "pole_task.xml") << "<world/>\n";
  Sequence s;
  s.file = (dir / "task.xml").string();
  s.line = 2;
  s.world = "pole_task.xml";
  EXPECT_EQ(FindSequenceWorld(s), (dir / "pole_task.xml").string());
  fs::remove(dir / "pole_task.xml");
  // Then as simpartner-sim finds a world: the shipped one.
  EXPECT_EQ(fs::canonical(FindSequenceWorld(s)), fs::canonical(kSource + "/models/worlds/pole_task.xml"));
  s.world = "no_such_world.xml";
  try {
    FindSequenceWorld(s);
    ADD_FAILURE() << "no error for a world that is nowhere";
  } catch (const ConfigError& e) {
    const std::string text = e.diagnostics().Format();
    EXPECT_EQ(text.rfind(s.file + ":2: sequence: world 'no_such_world.xml' is not found; tried:", 0), 0u)
        << text;
    EXPECT_NE(text.find("  " + (dir / "no_such_world.xml").string() + " (next to the sequence)"),
              std::string::npos)
        << text;
  }
  s.world.clear();
  EXPECT_EQ(FindSequenceWorld(s), "");
  EXPECT_EQ(WorldForSequence(s, kGen3World), kGen3World);
  fs::remove_all(dir);
}

TEST(SequenceOfflineCheck, ModelFromWorldHasTheRobotsTargets) {
  const model::World world = model::LoadWorldOrThrow(kGen3World);
  const model_t m = ModelFromWorld(world);
  ASSERT_EQ(m.robots.size(), 1u);
  EXPECT_EQ(m.robots[0].name, "WorkPartner");
  bool axle = false, scanner = false;
  for (const actuator_t& a : m.actuators) {
    if (a.name == "Axle1Motor") {
      axle = true;
      EXPECT_EQ(a.port, 1028);  // models/robots/workpartner_gen3.xml
      EXPECT_EQ(a.num_axes, 1);
      EXPECT_EQ(a.kind, actuator_t::KIND_JOINT_VELOCITY);
    }
  }
  for (const sensor_t& s : m.sensors) {
    if (s.name == "Scanner") {
      scanner = true;
      EXPECT_EQ(s.port, 1027);
      ASSERT_EQ(s.num_params, 3);
      EXPECT_EQ(s.params[0], 11);  // SPEC 4: 11 rays
    }
  }
  EXPECT_TRUE(axle);
  EXPECT_TRUE(scanner);
}

TEST(SequencerCommandLine, BadOptionsAreUsageErrors) {
  std::ostringstream out, err;
  EXPECT_EQ(RunSequencer({"--speed", "fast", "x.xml"}, out, err), 2);
  EXPECT_NE(err.str().find("--speed: value 'fast' is not a number"), std::string::npos) << err.str();
  EXPECT_EQ(RunSequencer({}, out, err), 2);
  EXPECT_EQ(RunSequencer({"--bogus"}, out, err), 2);
  EXPECT_NE(err.str().find("unknown option '--bogus'"), std::string::npos) << err.str();
  std::ostringstream help;
  EXPECT_EQ(RunSequencer({"--help"}, help, err), 0);
  EXPECT_NE(help.str().find("Exit status"), std::string::npos);
}

TEST(SequencerCommandLine, MissingFileIsNamed) {
  std::ostringstream out, err;
  EXPECT_EQ(RunSequencer({"--check", "/nonexistent/seq.xml"}, out, err), 2);
  // The data lookup's miss: the file, then every full path it tried.
  EXPECT_NE(err.str().find("/nonexistent/seq.xml: cannot read sequence file: not found; tried:"),
            std::string::npos) << err.str();
  EXPECT_NE(err.str().find("  /nonexistent/seq.xml (as given)"), std::string::npos) << err.str();
}

}  // namespace
}  // namespace simpartner::sequencer
