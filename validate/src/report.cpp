#include "simpartner/validate/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "simpartner/diagnostic.h"
#include "simpartner/validate/explanations.h"

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

// "" or "5 not applicable", of an engine's tally.
std::string NotApplicableText(const EngineTally& tally) {
  return tally.not_applicable == 0 ? std::string()
                                   : std::to_string(tally.not_applicable) + " not applicable";
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
  if (!result.not_applicable.empty()) {
    out << head << " NOT APPLICABLE: " << result.not_applicable << "\n";
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
    if (it == tallies.end()) it = tallies.insert(tallies.end(), EngineTally{r.engine, 0, 0, 0, {}});
    if (!r.not_applicable.empty()) {
      it->not_applicable += 1;
      continue;
    }
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
        << (t.not_applicable == 0 ? "" : ", " + NotApplicableText(t)) << " (mean "
        << MicrosecondsText(t.stepping.MicrosecondsPerStep()) << " µs per step)\n";
}

std::string MicrosecondsText(double microseconds) {
  if (!std::isfinite(microseconds)) return "-";
  char text[32];
  const char* format = microseconds >= 100 ? "%.0f" : microseconds >= 10 ? "%.1f" : "%.2f";
  std::snprintf(text, sizeof text, format, microseconds);
  return text;
}

namespace {

// The results of one experiment, one per engine (null where that engine
// did not run it), in the order the experiments ran.
struct ExperimentRuns {
  const ExperimentResult* first = nullptr;
  std::vector<const ExperimentResult*> by_engine;
};

std::vector<ExperimentRuns> GroupByExperiment(const std::vector<ExperimentResult>& results,
                                              const std::vector<EngineTally>& engines) {
  std::vector<ExperimentRuns> groups;
  for (const ExperimentResult& r : results) {
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const ExperimentRuns& g) { return g.first->name == r.name; });
    if (it == groups.end())
      it = groups.insert(groups.end(), ExperimentRuns{&r, {engines.size(), nullptr}});
    for (size_t e = 0; e < engines.size(); ++e)
      if (engines[e].engine == r.engine) it->by_engine[e] = &r;
  }
  return groups;
}

// The check labels of an experiment on all its engines, each once, in order.
std::vector<std::string> CheckLabels(const ExperimentRuns& runs) {
  std::vector<std::string> labels;
  for (const ExperimentResult* r : runs.by_engine)
    if (r != nullptr)
      for (const Check& c : r->checks)
        if (std::find(labels.begin(), labels.end(), c.label) == labels.end())
          labels.push_back(c.label);
  return labels;
}

const Check* FindCheck(const ExperimentResult* r, const std::string& label) {
  if (r == nullptr) return nullptr;
  for (const Check& c : r->checks)
    if (c.label == label) return &c;
  return nullptr;
}

std::string Link(const std::string& name) { return "[" + name + "](#" + name + ")"; }

std::string Verdict(bool pass) { return pass ? "PASS" : "**FAIL**"; }

// "ODE 15 of 15, MuJoCo 7 of 15"
std::string TallyText(const std::vector<EngineTally>& tallies) {
  std::string text;
  for (const EngineTally& t : tallies)
    text += (text.empty() ? "" : ", ") + EngineTitle(t.engine) + " " + std::to_string(t.passed) +
            " of " + std::to_string(t.run) +
            (t.not_applicable == 0 ? "" : " (" + NotApplicableText(t) + ")");
  return text;
}

// An engine's plots are drawn as `name_<engine>.png`, ODE's (the
// validated default's) under their own names.
Plot OnEngine(Plot plot, const std::string& engine) {
  if (engine == "ode") return plot;
  const fs::path file(plot.file);
  plot.file = file.stem().string() + "_" + engine + file.extension().string();
  return plot;
}

// "load average 0.42 (1 min), 1.10 (15 min)" from /proc/loadavg when the
// report is written: the µs per step are wall times, which other work on
// the machine inflates. "" where there is no /proc/loadavg.
std::string LoadAverageText() {
  std::ifstream in("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  if (!(in >> one >> five >> fifteen)) return "";
  char text[96];
  std::snprintf(text, sizeof text, "load average %.2f (1 min), %.2f (15 min)", one, fifteen);
  return text;
}

void WriteHeader(std::ostream& out, const std::vector<ExperimentResult>& results,
                 const std::vector<EngineTally>& tallies, const std::string& command,
                 const Parameters& params) {
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d", std::gmtime(&now));
  double wall = 0.0;
  for (const ExperimentResult& r : results) wall += r.wall_seconds;
  const std::string load = LoadAverageText();
  out << "# SimPartner validation\n\n"
      << "Written by `" << command << "` on " << date << " (experiments passed: "
      << TallyText(tallies) << "; " << Seconds(wall) << " of computing"
      << (load.empty() ? "" : "; " + load + " at the end")
      << "). Each experiment of SPEC 8, and those beyond the original, runs a "
      << "shipped world from `models/worlds/` through the sim library exactly as "
      << "`simpartner-sim` runs it (loader, `Simulation::Submit` with the step each command "
      << "applies at, `Simulation::Step`), as fast as possible, with step " << params.stepsize
      << " s (ODE: the " << params.stepper
      << " stepper) unless an experiment says otherwise, on each engine with the same "
      << "settings. Tolerances are the team's, the same for every engine; where a "
      << "target is physically wrong, the experiment's section says why, and the check still "
      << "fails. µs per step is the wall time of `Simulation::Step` alone, the mean over all "
      << "the experiment's steps.\n\n";
}

// Per experiment and engine: the verdict and the time of a step.
void WriteSummary(std::ostream& out, const std::vector<ExperimentRuns>& groups,
                  const std::vector<EngineTally>& tallies) {
  out << "## Summary\n\nExperiments passed: " << TallyText(tallies) << ".\n\n| experiment |";
  for (const EngineTally& t : tallies) out << " " << EngineTitle(t.engine) << " | µs per step |";
  out << "\n|---|";
  for (size_t e = 0; e < tallies.size(); ++e) out << "---|---:|";
  out << "\n";
  for (const ExperimentRuns& g : groups) {
    out << "| " << Link(g.first->name) << " |";
    for (const ExperimentResult* r : g.by_engine) {
      if (r == nullptr) out << " - | - |";
      else if (!r->not_applicable.empty()) out << " n/a | - |";
      else out << " " << Verdict(r->Passed()) << " | "
               << MicrosecondsText(r->stepping.MicrosecondsPerStep()) << " |";
    }
    out << "\n";
  }
}

// The failing checks of a report, each with its explanation (or none),
// numbered in the order the checks table meets them.
struct Failure {
  const ExperimentResult* run = nullptr;
  const Check* check = nullptr;  // null: the run failed
  const Explanation* why = nullptr;
};

class Failures {
 public:
  explicit Failures(const std::vector<Explanation>& table) : table_(table) {}
  // " ([why](#why-2))" or " (not yet explained)", for a failure's cell.
  std::string Add(const ExperimentResult* run, const Check* check) {
    const Explanation* why = Explain(table_, run->name, check ? check->label : "", run->engine);
    failures_.push_back(Failure{run, check, why});
    if (why == nullptr) return " (not yet explained)";
    return " ([why](#why-" + std::to_string(Number(why)) + "))";
  }
  const std::vector<Failure>& all() const { return failures_; }
  // 1, 2, ... per explanation, in the order of their first failure.
  int Number(const Explanation* why) {
    const auto it = std::find(order_.begin(), order_.end(), why);
    if (it != order_.end()) return static_cast<int>(it - order_.begin()) + 1;
    order_.push_back(why);
    return static_cast<int>(order_.size());
  }
  const std::vector<const Explanation*>& order() const { return order_; }

 private:
  const std::vector<Explanation>& table_;
  std::vector<Failure> failures_;
  std::vector<const Explanation*> order_;
};

// The figure and verdict of one check (or the failed run) on one engine;
// its own target and tolerance too where they differ from the row's (a
// target computed from the run: the steady state of the same vehicle).
std::string CheckCell(const ExperimentResult* r, const Check& row, Failures* failures) {
  if (r != nullptr && !r->error.empty()) return "run failed **FAIL**";
  if (r != nullptr && !r->not_applicable.empty()) return "n/a";
  const Check* c = FindCheck(r, row.label);
  if (c == nullptr) return "-";
  std::string cell = Cell(c->MeasuredText());
  if (c->TargetText() != row.TargetText() || c->ToleranceText() != row.ToleranceText())
    cell += " (target " + Cell(c->TargetText()) + " " + Cell(c->ToleranceText()) + ")";
  cell += " " + Verdict(c->pass);
  return c->pass ? cell : cell + failures->Add(r, c);
}

// Per check: target, tolerance and, per engine, the figure and verdict.
void WriteChecks(std::ostream& out, const std::vector<ExperimentRuns>& groups,
                 const std::vector<EngineTally>& tallies, Failures* failures) {
  out << "\n## Checks\n\n| experiment | check | target | tolerance |";
  for (const EngineTally& t : tallies) out << " " << EngineTitle(t.engine) << " |";
  out << "\n|---|---|---|---|";
  for (size_t e = 0; e < tallies.size(); ++e) out << "---|";
  out << "\n";
  for (const ExperimentRuns& g : groups) {
    for (const ExperimentResult* failed : g.by_engine) {
      if (failed == nullptr || failed->error.empty()) continue;
      out << "| " << Link(g.first->name) << " | the run: " << Cell(failed->error) << " | | |";
      for (const ExperimentResult* r : g.by_engine)
        out << " " << (r == failed ? "**FAIL**" + failures->Add(r, nullptr) : "-") << " |";
      out << "\n";
    }
    for (const std::string& label : CheckLabels(g)) {
      const ExperimentResult* any = nullptr;
      for (const ExperimentResult* r : g.by_engine)
        if (any == nullptr && FindCheck(r, label) != nullptr) any = r;
      const Check& c = *FindCheck(any, label);
      out << "| " << Link(g.first->name) << " | " << Cell(label) << " | "
          << Cell(c.TargetText()) << " | " << Cell(c.ToleranceText()) << " |";
      for (const ExperimentResult* r : g.by_engine)
        out << " " << CheckCell(r, c, failures) << " |";
      out << "\n";
    }
  }
}

std::string FailureText(const Failure& f) {
  std::string text = Link(f.run->name) + " on " + EngineTitle(f.run->engine) + ", ";
  if (f.check == nullptr) return text + "the run";
  const std::string tolerance = f.check->ToleranceText();
  return text + f.check->label + ": " + f.check->MeasuredText() + " against " +
         f.check->TargetText() + (tolerance == "-" ? "" : " " + tolerance);
}

// Every failing check under its engine's explanation, then those without.
void WriteWhy(std::ostream& out, const Failures& failures) {
  if (failures.all().empty()) return;
  out << "\n## Why checks fail\n\nFrom the engines' documented models "
      << "(`validate/src/explanations.cpp`), never by a tolerance: each engine is held to the "
      << "same targets.\n";
  for (size_t k = 0; k < failures.order().size(); ++k) {
    const Explanation* why = failures.order()[k];
    out << "\n<a id=\"why-" << k + 1 << "\"></a>\n**" << k + 1 << ".** " << why->why
        << "\n\n";
    for (const Failure& f : failures.all())
      if (f.why == why) out << "- " << FailureText(f) << "\n";
  }
  bool heading = false;
  for (const Failure& f : failures.all()) {
    if (f.why != nullptr) continue;
    if (!heading) out << "\nNot yet explained (for an experiment's own target, its section "
                         "says whether the target is at fault):\n\n";
    heading = true;
    out << "- " << FailureText(f) << "\n";
  }
}

// An experiment's section: verdicts, notes and plots per engine.
void WriteSection(std::ostream& out, const ExperimentRuns& g, size_t engines) {
  const ExperimentResult& first = *g.first;
  out << "\n<a id=\"" << first.name << "\"></a>\n## " << first.name << ": " << first.title
      << "\n\n";
  for (const ExperimentResult* r : g.by_engine) {
    if (r == nullptr) continue;
    if (!r->not_applicable.empty()) {
      out << (engines > 1 ? EngineTitle(r->engine) + ": " : std::string("Verdict: "))
          << "not applicable: " << r->not_applicable << ".\n\n";
      continue;
    }
    out << (engines > 1 ? EngineTitle(r->engine) + ": " : std::string("Verdict: "))
        << (r->Passed() ? "**PASS**" : "**FAIL**") << " (" << Seconds(r->sim_seconds)
        << " simulated in " << Seconds(r->wall_seconds) << ", "
        << MicrosecondsText(r->stepping.MicrosecondsPerStep()) << " µs per step; "
        << "`simpartner-validate --only " << r->name << " --engine " << r->engine << "`).\n\n";
  }
  if (!first.notes.empty()) out << first.notes << "\n\n";
  for (const ExperimentResult* r : g.by_engine) {
    if (r == nullptr || !r->not_applicable.empty()) continue;
    if (engines > 1) out << "### On " << EngineTitle(r->engine) << "\n\n";
    if (!r->error.empty()) out << "The run failed: `" << r->error << "`\n\n";
    if (r != &first && !r->notes.empty() && r->notes != first.notes) out << r->notes << "\n\n";
    for (const Plot& p : r->plots) {
      const Plot drawn = OnEngine(p, r->engine);
      out << "![" << drawn.title << "](" << drawn.file << ")\n\n";
    }
  }
}

}  // namespace

void WriteReport(const std::string& directory, const std::vector<ExperimentResult>& results,
                 const std::string& command, const Parameters& params,
                 const std::vector<Explanation>& explanations) {
  std::error_code error;
  fs::create_directories(directory, error);
  if (error) throw Error(directory + ": cannot create the report directory: " + error.message());
  for (const ExperimentResult& r : results)
    for (const Plot& p : r.plots) DrawPlot(OnEngine(p, r.engine), directory);

  const fs::path page = fs::path(directory) / "README.md";
  std::ofstream out(page);
  if (!out) throw Error(page.string() + ": cannot write the report");
  const std::vector<EngineTally> tallies = TallyByEngine(results);
  const std::vector<ExperimentRuns> groups = GroupByExperiment(results, tallies);
  WriteHeader(out, results, tallies, command, params);
  WriteSummary(out, groups, tallies);
  Failures failures(explanations);
  WriteChecks(out, groups, tallies, &failures);
  WriteWhy(out, failures);
  for (const ExperimentRuns& g : groups) WriteSection(out, g, tallies.size());
  if (!out) throw Error(page.string() + ": writing the report failed");
}

}  // namespace simpartner::validate
