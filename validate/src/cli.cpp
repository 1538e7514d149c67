#include "simpartner/validate/cli.h"

#include <filesystem>
#include <sstream>

#include "simpartner/data_paths.h"
#include "simpartner/edit_distance.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/report.h"

namespace simpartner::validate {
namespace {

std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string Names() {
  std::string names;
  for (const Experiment& e : Experiments()) names += (names.empty() ? "" : ", ") + e.name;
  return names;
}

// The experiments --only names (each NAME or NAME,NAME), else all (without
// the slow ones with --fast). Throws CommandLineError for an unknown name.
std::vector<const Experiment*> SelectExperiments(const CommandLine& command_line) {
  std::vector<const Experiment*> selected;
  for (const std::string& value : command_line.All("only")) {
    for (const std::string& name : SplitCommas(value)) {
      const Experiment* e = FindExperiment(name);
      if (e == nullptr) {
        std::vector<std::string> names;
        for (const Experiment& known : Experiments()) names.push_back(known.name);
        const std::string nearest = NearestName(name, names);
        throw CommandLineError("--only " + name + ": no such experiment" +
                               (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") +
                               "; one of: " + Names());
      }
      selected.push_back(e);
    }
  }
  if (selected.empty()) {
    for (const Experiment& e : Experiments())
      if (!(e.slow && command_line.Has("fast"))) selected.push_back(&e);
  }
  return selected;
}

// The directory holding worlds/ and robots/: --models, else the shipped
// models/ found as data. Throws CommandLineError or DataFileNotFound.
std::string ModelsDirectory(const CommandLine& command_line) {
  // models/worlds, not models: a build tree has a models/ of its own.
  const std::string dir =
      command_line.Has("models")
          ? command_line.Text("models")
          : std::filesystem::path(FindDataDirectory("models/worlds", "worlds directory"))
                .parent_path()
                .string();
  if (!std::filesystem::is_directory(std::filesystem::path(dir) / "worlds"))
    throw CommandLineError("--models " + dir + ": no worlds/ directory there");
  return dir;
}

// The engines --engine names (both: ODE, then MuJoCo), else the engine
// parameter (ode unless parameters.txt says otherwise).
std::vector<std::string> Engines(const CommandLine& command_line, const Parameters& params) {
  if (!command_line.Has("engine")) return {params.engine};
  const std::string engine = command_line.Text("engine");
  if (engine == "both") return {"ode", "mujoco"};
  return {engine};
}

// Runs each experiment on each engine in turn, printing its check lines
// (naming the engine when there are several) as it finishes.
std::vector<ExperimentResult> RunAll(const std::vector<const Experiment*>& selected,
                                     const std::vector<std::string>& engines,
                                     const Context& context, std::ostream& out,
                                     std::ostream& err) {
  const bool several = engines.size() > 1;
  std::vector<ExperimentResult> results;
  for (const Experiment* e : selected) {
    for (const std::string& engine : engines) {
      if (e->slow)
        err << "  ... " << e->name << (several ? " on " + EngineTitle(engine) : "")
            << ": slow experiment, progress follows" << std::endl;
      Context on = context;
      on.params.engine = engine;
      if (several && context.progress)
        on.progress = [&context, engine](const std::string& line) {
          context.progress(line + " (" + EngineTitle(engine) + ")");
        };
      results.push_back(RunExperiment(*e, on));
      PrintResult(results.back(), out, several);
      out.flush();
    }
  }
  return results;
}

}  // namespace

CommandLineSpec ValidateCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-validate";
  spec.summary =
      "Reruns the original's validation experiments (SPEC 8), ours beyond them, the soil "
      "experiments and the field sensors' rig through the sim library, headless and as fast "
      "as possible, and compares each with its analytic or real-robot target: one line per "
      "check (experiment, engine when there are several, what, measured, target, tolerance, "
      "PASS/FAIL; NOT APPLICABLE on an engine that cannot run it); exit status 1 if any check "
      "fails on any engine it ran.";
  spec.options = {
      Text("only", "NAME[,NAME]", "run only these experiments (see --list); may be repeated"),
      Switch("fast", "skip the slow experiments (long gaits, test track)"),
      Switch("list", "list the experiments and exit"),
      Text("engine", "ode|mujoco|both",
           "physics engine to run every experiment on; both = each experiment on ODE, then on "
           "MuJoCo (default: the engine parameter, ode)")
          .Choices({"ode", "mujoco", "both"}),
      Text("report", "DIR", "write DIR/README.md with a plot per experiment (gnuplot)"),
      Text("models", "DIR",
           "directory holding worlds/ and robots/ (default: the shipped models/, found like "
           "every data file: ./, $SIMPARTNER_DATA, the source tree of a build, the install)"),
  };
  spec.parameters = ParameterUse{
      {parameter_sections::kWorld, parameter_sections::kStepping, parameter_sections::kContact}};
  return spec;
}

int RunValidate(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  const CommandLineSpec spec = ValidateCommandLine();
  CommandLine command_line;
  if (const auto done = ReadCommandLine(spec, args, out, err, &command_line)) return *done;
  Context context;
  std::vector<const Experiment*> selected;
  std::vector<std::string> engines;
  try {
    context.params = LoadParameters(command_line.parameter_sources());
    engines = Engines(command_line, context.params);
    if (engines.size() == 1) context.params.engine = engines.front();
    if (PrintParametersIfAsked(command_line, context.params, out)) return 0;
    if (command_line.Has("list")) {
      for (const Experiment& e : Experiments())
        out << e.name << (e.slow ? " (slow)" : "") << ": " << e.title << "\n";
      return 0;
    }
    context.models_dir = ModelsDirectory(command_line);
    selected = SelectExperiments(command_line);
  } catch (const CommandLineError& e) {
    return ReportUsageError(spec, e.what(), err);
  } catch (const DiagnosticError& e) {
    err << e.diagnostics().Format() << "\n";
    return kUsageExitStatus;
  }
  context.progress = [&err](const std::string& line) { err << "  ... " << line << std::endl; };

  const std::vector<ExperimentResult> results = RunAll(selected, engines, context, out, err);
  const std::vector<EngineTally> tallies = TallyByEngine(results);
  PrintTallies(tallies, out);
  bool failed = false;
  for (const EngineTally& t : tallies) failed = failed || t.passed < t.run;

  const std::string report = command_line.Text("report");
  if (!report.empty()) {
    std::string command = spec.program;
    for (const std::string& a : args) command += " " + a;
    try {
      WriteReport(report, results, command, context.params);
      out << "report: " << (std::filesystem::path(report) / "README.md").string() << "\n";
    } catch (const Error& e) {
      err << spec.program << ": " << e.what() << "\n";
      return 2;
    }
  }
  return failed ? 1 : 0;
}

}  // namespace simpartner::validate
