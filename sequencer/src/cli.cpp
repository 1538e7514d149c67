#include "simpartner/sequencer/cli.h"

#include <cmath>
#include <cstdlib>
#include <ostream>
#include <string>

#include "simpartner/data_paths.h"
#include "simpartner/model/loader.h"
#include "simpartner/sequencer/check.h"
#include "simpartner/sequencer/player.h"
#include "simpartner/sequencer/sequence.h"

namespace simpartner::sequencer {
namespace {

bool Number(const std::string& text, double* out) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

void PrintNotes(const SequenceParseResult& parsed, std::ostream& err) {
  for (const std::string& note : parsed.notes) err << note << "\n";
}

}  // namespace

std::string Usage() {
  return R"(simpartner-sequencer: plays an XML command sequence against the sim on the bus.

  simpartner-sequencer FILE.xml [options]
  simpartner-sequencer --check FILE.xml [--environment WORLD.xml]

Times follow the sim's clock (SIM_STATE), never the wall clock; every
command carries the step it applies in, so a timed sequence gives the same
run at any speed. Before anything is sent the file is validated against its
DTD (version 1 or 2, built in) and against the model the sim announces.
A FILE or WORLD that is not found as given is looked for among the shipped
sequences/ and models/worlds/ ($SIMPARTNER_DATA, the source tree of a build,
the install's share/simpartner), e.g. simpartner-sequencer gen3_pole_task.xml.

Options:
  --lcm-url URL           the bus (default udpm://239.255.76.67:7667?ttl=0)
  --from-zero             'at' times count from sim time 0 instead of the
                          sim's step when the sequence starts (use with a sim
                          started paused: --startPaused=1, and --resume)
  --resume                resume a paused sim once the first commands are sent
  --speed X               set the sim's speed first (real-time factor; <= 0:
                          as fast as possible)
  --window S              send commands up to S s of sim time ahead (default 1)
  --model-timeout S       wait S s for SIM_MODEL (default 3)
  --silence-timeout S     stop when the sim sends nothing for S s (default 2)
  --quiet                 no progress lines
  --check FILE            validate only (no bus); also against the robots
                          (names, ports, value counts) of the world the
                          sequence names (<sequence world="...">) or of
                          --environment WORLD.xml, which must then be the
                          same world
  --help                  this text

Exit status: 0 played to the end (or --check found nothing); 1 stopped
while playing (refused by the sim, the sim restarted, faulted or went
silent, a wait timed out; the wheel motors are set to zero velocity);
2 the file or the command line is wrong (nothing was sent); 3 no sim on
the bus.
)";
}

int RunSequencer(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
                 int stop_fd) {
  PlayOptions options;
  options.stop_fd = stop_fd;
  std::string file, check_file, environment;
  auto usage_error = [&](const std::string& message) {
    err << "simpartner-sequencer: " << message << " (see --help)\n";
    return static_cast<int>(kInvalid);
  };
  for (size_t k = 0; k < args.size(); ++k) {
    std::string arg = args[k];
    std::string value;
    bool has_value = false;
    if (arg.rfind("--", 0) == 0) {
      const size_t eq = arg.find('=');
      if (eq != std::string::npos) {
        value = arg.substr(eq + 1);
        arg = arg.substr(0, eq);
        has_value = true;
      }
    }
    auto take = [&](std::string* out_value) {
      if (has_value) {
        *out_value = value;
        return true;
      }
      if (k + 1 >= args.size()) return false;
      *out_value = args[++k];
      return true;
    };
    auto take_number = [&](double* out_value) {
      std::string text;
      if (!take(&text)) return false;
      return Number(text, out_value);
    };
    if (arg == "--help" || arg == "-h") {
      out << Usage();
      return 0;
    } else if (arg == "--lcm-url") {
      if (!take(&options.url)) return usage_error("--lcm-url needs a URL");
    } else if (arg == "--from-zero") {
      options.from_zero = true;
    } else if (arg == "--resume") {
      options.resume = true;
    } else if (arg == "--quiet") {
      options.quiet = true;
    } else if (arg == "--speed") {
      double v = 0;
      if (!take_number(&v)) return usage_error("--speed needs a number");
      options.speed = v;
    } else if (arg == "--window") {
      if (!take_number(&options.window) || !(options.window > 0))
        return usage_error("--window needs a number of seconds above 0");
    } else if (arg == "--model-timeout") {
      if (!take_number(&options.model_timeout) || !(options.model_timeout > 0))
        return usage_error("--model-timeout needs a number of seconds above 0");
    } else if (arg == "--silence-timeout") {
      if (!take_number(&options.silence_timeout) || !(options.silence_timeout > 0))
        return usage_error("--silence-timeout needs a number of seconds above 0");
    } else if (arg == "--check") {
      if (!take(&check_file)) return usage_error("--check needs a sequence file");
    } else if (arg == "--environment") {
      if (!take(&environment)) return usage_error("--environment needs a world file");
    } else if (arg.rfind("--", 0) == 0) {
      return usage_error("unknown option '" + args[k] + "'");
    } else if (file.empty()) {
      file = arg;
    } else {
      return usage_error("one sequence file at a time ('" + file + "' and '" + arg + "')");
    }
  }
  // Sequence and world names are found like every data file (data_paths.h):
  // as given, else among the shipped sequences/ and models/worlds/.
  auto find = [&](std::string* name, bool world) {
    try {
      *name = world ? model::FindWorldFile(*name) : FindDataFile(*name, "sequence", {"sequences"});
      return true;
    } catch (const DataFileNotFound& e) {
      err << e.diagnostics().Format() << "\n";
      return false;
    }
  };
  if (!check_file.empty()) {
    if (!file.empty()) return usage_error("give the file to --check only");
    if (!find(&check_file, false) || (!environment.empty() && !find(&environment, true)))
      return kInvalid;
    const SequenceParseResult parsed = LoadSequenceFile(check_file);
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
      out << check_file << ": valid version " << parsed.sequence->version << " sequence, "
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
    out << check_file << ": valid version " << parsed.sequence->version << " sequence, "
        << parsed.sequence->CommandCount() << " commands, every target in '" << environment
        << "'" << (named_world ? " (the world the sequence names)" : "") << "\n";
    return kDone;
  }
  if (!environment.empty()) return usage_error("--environment goes with --check");
  if (file.empty()) return usage_error("no sequence file given");
  if (!find(&file, false)) {
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

}  // namespace simpartner::sequencer
