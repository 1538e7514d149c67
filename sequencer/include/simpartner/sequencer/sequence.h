// A sequence file (version 1: the original's <command>/<port> list;
// version 2: names, times, waits, ramps, repeats, comments) read into a
// timeline: segments of timed commands, each ending with a wait on a
// condition or at the end of the file. Repeats and ramps are unrolled here,
// so what is played is exactly the list a test can inspect.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"

namespace simpartner::sequencer {

// command_t::ACTION_* values, and kOriginal for a version-1 <command>: the
// original sent the command string to whatever had the port, so it becomes
// a SET for an actuator or an Echo sensor and SENSOR_PARAMS for another
// sensor (READ when the string is empty), decided against the model.
inline constexpr int8_t kOriginal = -1;

struct Command {
  int line = 0;
  std::string robot;    // "" = the sequence's robot, else the model's first
  std::string target;   // sensor or actuator name; "" when addressed by port
  int port = 0;         // legacy port, 0 when named
  int8_t action = kOriginal;
  std::string text;     // values as written ("1000,1000,100,0,0,0.2") or echo text
  double time = 0.0;    // [s] of sim time from its segment's start
  std::string element;  // the element it came from, for messages
};

struct Wait {
  enum class Kind { kTime, kJoint, kSensor };
  int line = 0;
  Kind kind = Kind::kTime;
  double start = 0.0;   // [s] from its segment's start: when waiting begins
  double sim_time = 0.0;            // kTime: sim time (as SIM_STATE says) to reach
  std::string robot;
  std::string joint;                // kJoint
  int axis = 0;
  double angle = 0.0, tolerance = 0.0;
  std::string sensor;               // kSensor
  int index = 0;                    // which value of the reading
  bool above = true;                // above (true) or below (false) threshold
  double threshold = 0.0;
  double timeout = std::numeric_limits<double>::infinity();  // [s] sim time
  std::string Describe() const;     // "joint Turner within 0.001 of 0.2972"
};

struct Note {
  int line = 0;
  double time = 0.0;
  std::string text;
};

// Commands timed from one start: the sequence's start or the moment the
// previous segment's wait was satisfied.
struct Segment {
  std::vector<Command> commands;    // in time order (file order for equal times)
  std::vector<Note> notes;
  double end = 0.0;                 // [s] where its timeline ends (pauses included)
  std::optional<Wait> wait;         // ends the segment; absent for the last one
};

struct Sequence {
  std::string file;
  int version = 0;
  std::string name, robot, description;
  // The world file the sequence is made for, as written (version 2's
  // world attribute, a NAME.xml); "" when it names none. FindSequenceWorld
  // (check.h) finds the file.
  std::string world;
  int line = 0;                     // of the <sequence> element
  bool rootless = false;            // a bare list of <command>s, read as version 1
  std::vector<Segment> segments;    // at least one
  size_t CommandCount() const;
};

struct SequenceParseResult {
  std::optional<Sequence> sequence;  // set only when there were no errors
  DiagnosticList diagnostics;
  std::vector<std::string> notes;    // things the user should know (rootless file)
};

// Most commands a file may unroll to (repeats and ramps), so that a small
// file cannot take the memory of the machine.
inline constexpr size_t kMaxCommands = 250000;

// max_commands: a lower bound than kMaxCommands (the fuzz target's, so
// that each input stays fast).
SequenceParseResult ParseSequence(const std::string& xml, const std::string& file_name,
                                  size_t max_commands = kMaxCommands);
SequenceParseResult LoadSequenceFile(const std::string& path);

// The DTD texts built into the program (sequencer/dtd/), version 1 or 2.
const std::string& SequenceDtd(int version);

// The numbers of a command string: "1000, 1000,100" -> {1000, 1000, 100};
// false with a message naming the bad item.
bool ParseValues(const std::string& text, std::vector<double>* values, std::string* error);

}  // namespace simpartner::sequencer
