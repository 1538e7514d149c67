#include "simpartner/validate/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "simpartner/diagnostic.h"

namespace simpartner::validate {
namespace {

namespace fs = std::filesystem;

std::string Pad(std::string text, size_t width) {
  if (text.size() < width) text.resize(width, ' ');
  return text;
}

std::string Seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, s < 1.0 ? "%.2f s" : "%.1f s", s);
  return text;
}

// A '|' inside a Markdown table cell is written \|.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

void PrintResult(const ExperimentResult& result, std::ostream& out, bool name_engine) {
  const std::string head =
      Pad(result.name, 20) + (name_engine ? " " + Pad(result.engine, 6) : std::string());
  if (!result.error.empty()) {
    out << head << " ERROR: " << result.error << "  FAIL\n";
    return;
  }
  for (const Check& c : result.checks) {
    out << head << " " << Pad(c.label, 62) << " measured "
        << Pad(c.MeasuredText(), 16) << " target " << Pad(c.TargetText(), 16) << " tol "
        << Pad(c.ToleranceText(), 15) << " " << (c.pass ? "PASS" : "FAIL") << "\n";
  }
}

std::string EngineTitle(const std::string& engine) {
  if (engine == "ode") return "ODE";
  if (engine == "mujoco") return "MuJoCo";
  return engine;
}

std::vector<EngineTally> TallyByEngine(const std::vector<ExperimentResult>& results) {
  std::vector<EngineTally> tallies;
  for (const ExperimentResult& r : results) {
    auto it = std::find_if(tallies.begin(), tallies.end(),
                           [&](const EngineTally& t) { return t.engine == r.engine; });
    if (it == tallies.end()) it = tallies.insert(tallies.end(), EngineTally{r.engine, 0, 0, {}});
    it->passed += r.Passed() ? 1 : 0;
    it->run += 1;
    it->stepping.steps += r.stepping.steps;
    it->stepping.seconds += r.stepping.seconds;
  }
  return tallies;
}

void PrintTallies(const std::vector<EngineTally>& tallies, std::ostream& out) {
  for (const EngineTally& t : tallies)
    out << t.passed << " of " << t.run << " experiments passed on " << EngineTitle(t.engine)
        << " (mean " << MicrosecondsText(t.stepping.MicrosecondsPerStep()) << " µs per step)\n";
}

std::string MicrosecondsText(double microseconds) {
  if (!std::isfinite(microseconds)) return "-";
  char text[32];
  const char* format = microseconds >= 100 ? "%.0f" : microseconds >= 10 ? "%.1f" : "%.2f";
  std::snprintf(text, sizeof text, format, microseconds);
  return text;
}

void WriteReport(const std::string& directory, const std::vector<ExperimentResult>& results,
                 const std::string& command, const Parameters& params) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) throw Error(directory + ": cannot create the report directory: " + error.message());
  for (const ExperimentResult& r : results)
    for (const Plot& p : r.plots) DrawPlot(p, directory);

  const fs::path page = fs::path(directory) / "README.md";
  std::ofstream out(page);
  if (!out) throw Error(page.string() + ": cannot write the report");
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  int passed = 0;
  double wall = 0.0;
  for (const ExperimentResult& r : results) {
    passed += r.Passed() ? 1 : 0;
    wall += r.wall_seconds;
  }
  out << "# SimPartner validation\n\n"
      << "Written by `" << command << "` on " << date << " (" << passed << " of "
      << results.size() << " experiments passed, " << Seconds(wall)
      << " of computing). Each experiment of SPEC 8, and two beyond the original, runs a "
      << "shipped world from `models/worlds/` through the sim library exactly as "
      << "`simpartner-sim` runs it (loader, `Simulation::Submit` with the step each command "
      << "applies at, `Simulation::Step`), as fast as possible, with step "
      << params.stepsize << " s and the " << params.stepper
      << " stepper unless an experiment says otherwise. Tolerances are the team's (issue 5); "
      << "where a target is physically wrong, the experiment's section says why, and the "
      << "check still fails.\n\n";
  out << "## Summary\n\n| experiment | check | measured | target | tolerance | verdict |\n"
      << "|---|---|---|---|---|---|\n";
  for (const ExperimentResult& r : results) {
    if (!r.error.empty()) {
      out << "| [" << r.name << "](#" << r.name << ") | run failed: " << Cell(r.error)
          << " | | | | **FAIL** |\n";
      continue;
    }
    for (const Check& c : r.checks) {
      out << "| [" << r.name << "](#" << r.name << ") | " << Cell(c.label) << " | "
          << Cell(c.MeasuredText()) << " | " << Cell(c.TargetText()) << " | "
          << Cell(c.ToleranceText()) << " | " << (c.pass ? "PASS" : "**FAIL**") << " |\n";
    }
  }
  std::string failing;
  for (const ExperimentResult& r : results)
    if (!r.Passed()) failing += (failing.empty() ? "" : ", ") + ("[" + r.name + "](#" + r.name + ")");
  if (!failing.empty())
    out << "\nFailing: " << failing
        << ". Each section says whether the simulation or the target is at fault.\n";
  for (const ExperimentResult& r : results) {
    out << "\n<a id=\"" << r.name << "\"></a>\n## " << r.name << ": " << r.title << "\n\n";
    out << "Verdict: " << (r.Passed() ? "**PASS**" : "**FAIL**") << " (" << Seconds(r.sim_seconds)
        << " simulated in " << Seconds(r.wall_seconds) << "; `simpartner-validate --only "
        << r.name << "`).\n\n";
    if (!r.error.empty()) out << "The run failed: `" << r.error << "`\n\n";
    if (!r.notes.empty()) out << r.notes << "\n\n";
    for (const Plot& p : r.plots) out << "![" << p.title << "](" << p.file << ")\n\n";
  }
  if (!out) throw Error(page.string() + ": writing the report failed");
}

}  // namespace simpartner::validate
