#include "simpartner/validate/cli.h"

#include <filesystem>
#include <sstream>

#include "simpartner/data_paths.h"
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

}  // namespace

const std::vector<FlagSpec>& ValidateFlags() {
  static const std::vector<FlagSpec> kFlags = {
      {"only", true, "run only this experiment (NAME or NAME,NAME; see --list)"},
      {"fast", false, "skip the slow experiments (long gaits, test track)"},
      {"list", false, "list the experiments and exit"},
      {"report", true, "write DIR/README.md with a plot per experiment (gnuplot)"},
      {"models", true,
       "directory holding worlds/ and robots/ (default: the shipped models/, found like "
       "every data file: ./, $SIMPARTNER_DATA, the source tree of a build, the install)"},
  };
  return kFlags;
}

const char* ValidateSummary() {
  return "Reruns the original's validation experiments (SPEC 8) and two more "
         "through the sim library, headless and as fast as possible, and "
         "compares each with its analytic or real-robot target: one line per "
         "check (experiment, what, measured, target, tolerance, PASS/FAIL); "
         "exit status 1 if any check fails.";
}

int RunValidate(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  Context context;
  CommandLine command_line;
  try {
    command_line = ParseCommandLine(argc, argv, ValidateFlags());
    if (command_line.Has("help")) {
      out << FormatUsage("simpartner-validate", ValidateSummary(), ValidateFlags(),
                         {parameter_sections::kWorld, parameter_sections::kStepping,
                          parameter_sections::kContact});
      return 0;
    }
    if (!command_line.positional.empty()) {
      err << "simpartner-validate: unexpected argument '" << command_line.positional.front()
          << "'\n";
      return 2;
    }
    context.params = LoadParameters(command_line);
    if (PrintParametersIfAsked(command_line, context.params, out)) return 0;
  } catch (const DiagnosticError& e) {
    err << e.diagnostics().Format() << "\n";
    return 2;
  }
  if (command_line.Has("list")) {
    for (const Experiment& e : Experiments())
      out << e.name << (e.slow ? " (slow)" : "") << ": " << e.title << "\n";
    return 0;
  }
  if (command_line.Has("models")) {
    context.models_dir = command_line.Value("models", "");
  } else {
    try {
      // models/worlds, not models: a build tree has a models/ of its own.
      context.models_dir =
          std::filesystem::path(FindDataDirectory("models/worlds", "worlds directory"))
              .parent_path()
              .string();
    } catch (const DataFileNotFound& e) {
      err << e.diagnostics().Format() << "\n";
      return 2;
    }
  }
  if (!std::filesystem::is_directory(std::filesystem::path(context.models_dir) / "worlds")) {
    err << "simpartner-validate: --models " << context.models_dir
        << ": no worlds/ directory there\n";
    return 2;
  }

  std::vector<const Experiment*> selected;
  for (const auto& [flag, value] : command_line.flag_values) {
    if (flag != "only") continue;
    for (const std::string& name : SplitCommas(value)) {
      const Experiment* e = FindExperiment(name);
      if (e == nullptr) {
        err << "simpartner-validate: --only " << name << ": no such experiment (one of: "
            << Names() << ")\n";
        return 2;
      }
      selected.push_back(e);
    }
  }
  if (selected.empty()) {
    for (const Experiment& e : Experiments())
      if (!(e.slow && command_line.Has("fast"))) selected.push_back(&e);
  }
  context.progress = [&err](const std::string& line) { err << "  ... " << line << std::endl; };

  std::vector<ExperimentResult> results;
  int failed = 0;
  for (const Experiment* e : selected) {
    if (e->slow) err << "  ... " << e->name << ": slow experiment, progress follows" << std::endl;
    results.push_back(RunExperiment(*e, context));
    PrintResult(results.back(), out);
    out.flush();
    failed += results.back().Passed() ? 0 : 1;
  }
  out << (selected.size() - failed) << " of " << selected.size() << " experiments passed\n";

  const std::string report = command_line.Value("report", "");
  if (!report.empty()) {
    std::string command = "simpartner-validate";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    try {
      WriteReport(report, results, command, context.params);
      out << "report: " << (std::filesystem::path(report) / "README.md").string() << "\n";
    } catch (const Error& e) {
      err << "simpartner-validate: " << e.what() << "\n";
      return 2;
    }
  }
  return failed == 0 ? 0 : 1;
}

}  // namespace simpartner::validate
