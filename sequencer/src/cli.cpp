#include "simpartner/sequencer/cli.h"

#include <ostream>
#include <string>

#include "simpartner/data_paths.h"
#include "simpartner/model/loader.h"
#include "simpartner/sequencer/check.h"
#include "simpartner/sequencer/player.h"
#include "simpartner/sequencer/sequence.h"

namespace simpartner::sequencer {
namespace {

void PrintNotes(const SequenceParseResult& parsed, std::ostream& err) {
  for (const std::string& note : parsed.notes) err << note << "\n";
}

// Sequence and world names are found like every data file (data_paths.h):
// as given, else among the shipped sequences/ and models/worlds/.
bool Find(std::string* name, bool world, std::ostream& err) {
  try {
    *name = world ? model::FindWorldFile(*name) : FindDataFile(*name, "sequence", {"sequences"});
    return true;
  } catch (const DataFileNotFound& e) {
    err << e.diagnostics().Format() << "\n";
    return false;
  }
}

// --check FILE [--environment WORLD]: validates without the bus, against
// the world given or the one the sequence names, if any.
int Check(std::string file, std::string environment, std::ostream& out, std::ostream& err) {
  if (!Find(&file, false, err) || (!environment.empty() && !Find(&environment, true, err)))
    return kInvalid;
  const SequenceParseResult parsed = LoadSequenceFile(file);
  PrintNotes(parsed, err);
  if (!parsed.sequence) {
    err << parsed.diagnostics.Format() << "\n";
    return kInvalid;
  }
  // Without --environment, the world the sequence names (if any).
  const bool named_world = environment.empty() && !parsed.sequence->world.empty();
  try {
    environment = WorldForSequence(*parsed.sequence, environment);
  } catch (const DiagnosticError& e) {
    err << e.diagnostics().Format() << "\n";
    return kInvalid;
  }
  if (environment.empty()) {
    out << file << ": valid version " << parsed.sequence->version << " sequence, "
        << parsed.sequence->CommandCount() << " commands (names and ports not checked: "
        << "give --environment WORLD.xml)\n";
    return kDone;
  }
  const model::WorldLoadResult world = model::LoadWorldFile(environment);
  if (!world.world) {
    err << world.diagnostics.Format() << "\n";
    err << environment << ": the world does not load\n";
    return kInvalid;
  }
  const DiagnosticList problems = CheckSequence(*parsed.sequence, ModelFromWorld(*world.world), nullptr);
  if (!problems.empty()) {
    err << problems.Format() << "\n";
    return kInvalid;
  }
  out << file << ": valid version " << parsed.sequence->version << " sequence, "
      << parsed.sequence->CommandCount() << " commands, every target in '" << environment << "'"
      << (named_world ? " (the world the sequence names)" : "") << "\n";
  return kDone;
}

// FILE: loads it and plays it against the sim on the bus.
int LoadAndPlay(std::string file, const PlayOptions& options, std::ostream& out, std::ostream& err) {
  if (!Find(&file, false, err)) {
    err << file << ": not played; nothing was sent\n";
    return kInvalid;
  }
  const SequenceParseResult parsed = LoadSequenceFile(file);
  PrintNotes(parsed, err);
  if (!parsed.sequence) {
    err << parsed.diagnostics.Format() << "\n";
    err << file << ": not played; nothing was sent\n";
    return kInvalid;
  }
  return Play(*parsed.sequence, options, out, err);
}

}  // namespace

CommandLineSpec SequencerCommandLine() {
  const PlayOptions defaults;
  CommandLineSpec spec;
  spec.program = "simpartner-sequencer";
  spec.summary =
      "Plays an XML command sequence against the sim on the bus; with --check FILE.xml\n"
      "[--environment WORLD.xml] it only validates the file.\n"
      "\n"
      "Times follow the sim's clock (SIM_STATE), never the wall clock; every\n"
      "command carries the step it applies in, so a timed sequence gives the same\n"
      "run at any speed. Before anything is sent the file is validated against its\n"
      "DTD (version 1 or 2, built in) and against the model the sim announces.\n"
      "A FILE or WORLD that is not found as given is looked for among the shipped\n"
      "sequences/ and models/worlds/ ($SIMPARTNER_DATA, the source tree of a build,\n"
      "the install's share/simpartner), e.g. simpartner-sequencer gen3_pole_task.xml.";
  spec.options = {
      Text("lcm-url", "URL", "the bus (default " + defaults.url + ")"),
      Switch("from-zero",
             "'at' times count from sim time 0 instead of the sim's step when the sequence "
             "starts (use with a sim started paused: --startPaused=1, and --resume)"),
      Switch("resume", "resume a paused sim once the first commands are sent"),
      Number("speed", "X", "set the sim's speed first (real-time factor; <= 0: as fast as possible)"),
      Number("window", "S", "send commands up to S s of sim time ahead (default 1)").Above(0),
      Number("model-timeout", "S", "wait S s for SIM_MODEL (default 3)").Above(0),
      Number("silence-timeout", "S", "stop when the sim sends nothing for S s (default 2)").Above(0),
      Switch("quiet", "no progress lines"),
      Text("check", "FILE",
           "validate only (no bus); also against the robots (names, ports, value counts) of "
           "the world the sequence names (<sequence world=\"...\">) or of --environment "
           "WORLD.xml, which must then be the same world"),
      Text("environment", "WORLD.xml", "the world --check checks against"),
  };
  spec.positionals = {Positional{"FILE.xml", 0, 1}};
  spec.epilogue =
      "Exit status: 0 played to the end (or --check found nothing); 1 stopped\n"
      "while playing (refused by the sim, the sim restarted, faulted or went\n"
      "silent, a wait timed out; the wheel motors are set to zero velocity);\n"
      "2 the file or the command line is wrong (nothing was sent); 3 no sim on\n"
      "the bus.";
  return spec;
}

int RunSequencer(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                 int stop_fd) {
  const CommandLineSpec spec = SequencerCommandLine();
  CommandLine command_line;
  if (const auto done = ReadCommandLine(spec, args, out, err, &command_line)) return *done;
  const std::vector<std::string>& files = command_line.positional();
  const std::string environment = command_line.Text("environment");
  if (command_line.Has("check")) {
    if (!files.empty()) return ReportUsageError(spec, "give the file to --check only", err);
    return Check(command_line.Text("check"), environment, out, err);
  }
  if (!environment.empty()) return ReportUsageError(spec, "--environment goes with --check", err);
  if (files.empty()) return ReportUsageError(spec, "no sequence file given", err);
  PlayOptions options;
  options.stop_fd = stop_fd;
  options.url = command_line.Text("lcm-url", options.url);
  options.from_zero = command_line.Has("from-zero");
  options.resume = command_line.Has("resume");
  options.quiet = command_line.Has("quiet");
  if (command_line.Has("speed")) options.speed = command_line.Number("speed", 0);
  options.window = command_line.Number("window", options.window);
  options.model_timeout = command_line.Number("model-timeout", options.model_timeout);
  options.silence_timeout = command_line.Number("silence-timeout", options.silence_timeout);
  return LoadAndPlay(files.front(), options, out, err);
}

}  // namespace simpartner::sequencer
