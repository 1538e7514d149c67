#include "simpartner/batch/batch_file.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "batch_dtd.h"  // generated: kBatchDtdText
#include "simpartner/bounded_file.h"
#include "simpartner/data_paths.h"
#include "simpartner/model/loader.h"
#include "simpartner/model/robot_choice.h"
#include "simpartner/parameters.h"
#include "simpartner/programs.h"
#include "simpartner/text.h"
#include "simpartner/xml_document.h"

namespace simpartner::batch {
namespace {

namespace fs = std::filesystem;
using xml::Attribute;
using xml::Line;

// The placeholders every controller may name besides the sweep's variables.
const std::set<std::string> kBuiltInPlaceholders = {"url", "seed", "run", "batch"};

bool IsPlainName(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// The {names} of a command line.
std::vector<std::string> Placeholders(const std::string& text) {
  std::vector<std::string> names;
  for (size_t open = text.find('{'); open != std::string::npos; open = text.find('{', open + 1)) {
    const size_t close = text.find('}', open);
    if (close == std::string::npos) break;
    names.push_back(text.substr(open + 1, close - open - 1));
  }
  return names;
}

class Reader {
 public:
  Reader(std::string file_name, DiagnosticList* diagnostics)
      : file_(std::move(file_name)), diagnostics_(diagnostics) {
    const fs::path parent = fs::path(file_).parent_path();
    dir_ = parent.empty() ? "." : parent.string();
  }

  std::optional<BatchFile> Read(const xmlNode* root) {
    batch_.file = file_;
    batch_.name = *Attribute(root, "name");
    if (!IsPlainName(batch_.name))
      Error(root, "name '" + batch_.name + "': letters, digits, _ - and . only (it names files)");
    World(xml::Child(root, "world"), xml::Child(root, "robot"));
    for (const xmlNode* p : xml::Children(root, "parameter")) Parameter(p);
    Duration(xml::Child(root, "duration"));
    Controller(xml::Child(root, "controller"), xml::Child(root, "sequence"));
    Seeds(xml::Child(root, "seeds"));
    if (const xmlNode* sweep = xml::Child(root, "sweep")) Sweep(sweep);
    CheckRunCount(root);
    for (const xmlNode* f : xml::Children(root, "figure")) Figure(f);
    CheckPlaceholders(xml::Child(root, "controller"));
    if (!diagnostics_->empty()) return std::nullopt;
    return batch_;
  }

 private:
  void Error(const xmlNode* node, const std::string& message) {
    xml::AddAt(diagnostics_, file_, node, message);
  }

  // As given, next to the batch file, then as every program finds data.
  std::optional<std::string> Find(const xmlNode* node, const std::string& name,
                                   const std::string& kind, const std::vector<std::string>& dirs) {
    const fs::path beside = fs::path(dir_) / name;
    if (fs::path(name).is_relative() && fs::is_regular_file(beside)) return beside.string();
    try {
      return FindDataFile(name, kind, dirs);
    } catch (const DataFileNotFound& e) {
      Error(node, kind + " '" + name + "' not found (" + std::to_string(e.tried().size()) +
                      " places tried, the first " + e.tried().front().path + ")");
      return std::nullopt;
    }
  }

  void World(const xmlNode* world, const xmlNode* robot) {
    if (robot) batch_.robot = xml::Text(robot);
    const auto path = Find(world, xml::Text(world), "world", {"models/worlds"});
    if (!path) return;
    batch_.world = *path;
    const model::WorldLoadResult loaded = model::LoadWorldFile(*path);
    if (!loaded.world)
      Error(world, "world '" + *path + "' does not load: " + loaded.diagnostics.Format());
    else
      world_ = *loaded.world;
  }

  // Checks key=value as parameters.txt would; the problems at this line.
  bool CheckParameter(const xmlNode* node, const std::string& key, const std::string& value) {
    Parameters params;
    DiagnosticList problems;
    ParseParametersText(key + "=" + value, file_, &params, &problems);
    for (const Diagnostic& d : problems.items()) Error(node, d.message);
    return problems.empty();
  }

  void Parameter(const xmlNode* node) {
    const std::string key = *Attribute(node, "key"), value = xml::Text(node);
    if (key == "lcmUrl" || key == "speed" || key == "startPaused" || key == "duration")
      Error(node, "parameter '" + key + "' is the batch's to set (every run has its own bus, "
                  "starts paused, runs as fast as possible for <duration>)");
    else if (key == "environment")
      Error(node, "the world is <world>'s (or a <vary key=\"environment\">'s, a world per run)");
    else if (CheckParameter(node, key, value))
      batch_.parameters.emplace_back(key, value);
  }

  void Duration(const xmlNode* node) {
    char* end = nullptr;
    const std::string text = xml::Text(node);
    batch_.duration = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(batch_.duration) || batch_.duration <= 0 ||
        batch_.duration > 1e6)
      Error(node, "duration '" + text + "': seconds of sim time above 0, at most 1e6");
  }

  void Controller(const xmlNode* controller, const xmlNode* sequence) {
    if (controller) {
      batch_.controller = xml::Text(controller);
      const std::vector<std::string> words = Words(batch_.controller);
      if (words.empty()) Error(controller, "the controller command is empty");
      else ControllerProgram(controller, words.front());
      return;
    }
    const auto path = Find(sequence, *Attribute(sequence, "file"), "sequence", {"sequences"});
    if (path) batch_.sequence = *path;
  }

  // The controller's program is found now, as each run will start it (a
  // placeholder in its name is found at the run).
  void ControllerProgram(const xmlNode* controller, const std::string& program) {
    if (program.find('{') != std::string::npos || !FindProgram(program).empty()) return;
    if (program.find('/') != std::string::npos)
      Error(controller, "controller program '" + program + "' is not an executable file");
    else
      Error(controller, "controller program '" + program +
                            "' is neither a program of this build or install nor on PATH");
  }

  void Seeds(const xmlNode* node) {
    if (!node) {
      batch_.seeds = {0};
      return;
    }
    std::set<long long> seen;
    for (const std::string& word : Words(xml::Text(node))) {
      char* end = nullptr;
      const long long seed = std::strtoll(word.c_str(), &end, 10);
      if (*end != '\0') Error(node, "seed '" + word + "' is not a whole number");
      else if (!seen.insert(seed).second) Error(node, "seed " + word + " is given twice");
      else batch_.seeds.push_back(seed);
    }
    if (batch_.seeds.empty()) Error(node, "no seeds (leave <seeds> out for one run per value)");
  }

  void Sweep(const xmlNode* sweep) {
    batch_.grid = Attribute(sweep, "mode").value_or("grid") == "grid";
    std::set<std::string> names;
    for (const xmlNode* node : xml::Children(sweep, "vary")) {
      Vary vary;
      vary.line = Line(node);
      const auto key = Attribute(node, "key"), name = Attribute(node, "name");
      if (key.has_value() == name.has_value()) {
        Error(node, "a <vary> gives exactly one of key (a parameter) and name (a variable)");
        continue;
      }
      vary.is_parameter = key.has_value();
      vary.name = key ? *key : *name;
      vary.values = Words(*Attribute(node, "values"));
      if (vary.values.empty()) Error(node, "'" + vary.name + "' has no values");
      if (!names.insert(vary.name).second) Error(node, "'" + vary.name + "' is swept twice");
      CheckVary(node, &vary);
      batch_.sweep.push_back(std::move(vary));
    }
    CheckListLengths(sweep);
  }

  // A sweep over worlds (key environment) or robots (key robot, the sim's
  // --robot): each value found now, so a run never starts on a name that is
  // not there.
  bool CheckScenario(const xmlNode* node, Vary* vary) {
    if (vary->name == "environment") {
      for (std::string& value : vary->values)
        if (const auto path = Find(node, value, "world", {"models/worlds"})) value = *path;
      return true;
    }
    if (vary->name != "robot") return false;
    if (!batch_.robot.empty()) Error(node, "the robot is fixed by <robot> and swept here");
    for (const std::string& value : vary->values) {
      try {
        model::RobotFileOf(value);
      } catch (const ConfigError& e) {
        for (const Diagnostic& d : e.diagnostics().items()) Error(node, d.message);
      }
    }
    return true;
  }

  void CheckVary(const xmlNode* node, Vary* swept) {
    if (swept->is_parameter && CheckScenario(node, swept)) return;
    const Vary& vary = *swept;
    if (!vary.is_parameter) {
      if (!IsPlainName(vary.name) || kBuiltInPlaceholders.count(vary.name))
        Error(node, "variable name '" + vary.name + "': letters, digits, _ - . and not one of "
                    "url, seed, run, batch");
      return;
    }
    for (const auto& fixed : batch_.parameters)
      if (fixed.first == vary.name)
        Error(node, "parameter '" + vary.name + "' is fixed above and swept here");
    for (const std::string& value : vary.values)
      if (!CheckParameter(node, vary.name, value)) break;  // one message per key suffices
  }

  void CheckListLengths(const xmlNode* sweep) {
    if (batch_.grid || batch_.sweep.empty()) return;
    for (const Vary& v : batch_.sweep)
      if (v.values.size() != batch_.sweep.front().values.size())
        Error(sweep, "mode list: '" + v.name + "' has " + std::to_string(v.values.size()) +
                         " values, '" + batch_.sweep.front().name + "' " +
                         std::to_string(batch_.sweep.front().values.size()));
  }

  // At most kMaxRuns runs (counted in double: a grid's product may be huge).
  void CheckRunCount(const xmlNode* root) {
    double runs = static_cast<double>(batch_.seeds.size());
    if (!batch_.sweep.empty() && !batch_.grid)
      runs *= static_cast<double>(batch_.sweep.front().values.size());
    else
      for (const Vary& v : batch_.sweep) runs *= static_cast<double>(v.values.size());
    if (runs <= kMaxRuns) return;
    const xmlNode* sweep = xml::Child(root, "sweep");
    Error(sweep ? sweep : root, "the batch is " + ShortestNumber(runs) +
                                    " runs (the seeds times the sweep's combinations); at most " +
                                    std::to_string(kMaxRuns) + ": split it into several batches");
  }

  void Figure(const xmlNode* node) {
    batch::Figure f;
    f.line = Line(node);
    f.name = *Attribute(node, "name");
    f.body = *Attribute(node, "body");
    const std::string q = *Attribute(node, "quantity");
    f.quantity = q == "x" ? Quantity::kX : q == "y" ? Quantity::kY : q == "z" ? Quantity::kZ
                 : q == "path_length" ? Quantity::kPathLength
                 : q == "final_speed" ? Quantity::kFinalSpeed : Quantity::kPeakContactForce;
    for (const batch::Figure& other : batch_.figures)
      if (other.name == f.name) Error(node, "figure '" + f.name + "' is named twice");
    if (!IsPlainName(f.name)) Error(node, "figure name '" + f.name + "': letters, digits, _ - .");
    if (world_ && batch_.robot.empty() && !Swept("environment") && !Swept("robot") &&
        !HasBody(f.body))
      Error(node, "body '" + f.body + "' is in none of the world's robots and objects");
    batch_.figures.push_back(f);
  }

  bool Swept(const std::string& key) const {
    for (const Vary& v : batch_.sweep)
      if (v.is_parameter && v.name == key) return true;
    return false;
  }

  bool HasBody(const std::string& name) const {
    for (const model::Body& b : world_->objects)
      if (b.name == name) return true;
    for (const model::RobotInstance& r : world_->robots)
      if (r.robot.FindBody(name) != nullptr) return true;
    return false;
  }

  // Every {name} of the controller is known, every variable is used, and
  // the controller is told its bus.
  void CheckPlaceholders(const xmlNode* controller) {
    if (!controller) {
      for (const Vary& v : batch_.sweep)
        if (!v.is_parameter)
          diagnostics_->Add(file_, v.line, "vary", "variable '" + v.name +
                                                       "' is for a controller; a sequence has none");
      return;
    }
    const std::vector<std::string> used = Placeholders(batch_.controller);
    std::set<std::string> known = kBuiltInPlaceholders;
    for (const Vary& v : batch_.sweep)
      if (!v.is_parameter) known.insert(v.name);
    for (const std::string& name : used)
      if (!known.count(name)) Error(controller, "{" + name + "} is neither url, seed, run, batch "
                                                "nor a variable of the sweep");
    if (std::find(used.begin(), used.end(), "url") == used.end())
      Error(controller, "the controller is not told its bus: name {url} where it takes one "
                        "(every run has a bus of its own)");
    for (const Vary& v : batch_.sweep)
      if (!v.is_parameter && std::find(used.begin(), used.end(), v.name) == used.end())
        diagnostics_->Add(file_, v.line, "vary",
                          "variable '" + v.name + "' is never used: the controller has no {" +
                              v.name + "}");
  }

  std::string file_, dir_;
  DiagnosticList* diagnostics_;
  BatchFile batch_;
  std::optional<model::World> world_;
};

}  // namespace

const char* QuantityName(Quantity quantity) {
  switch (quantity) {
    case Quantity::kX: return "x";
    case Quantity::kY: return "y";
    case Quantity::kZ: return "z";
    case Quantity::kPathLength: return "path_length";
    case Quantity::kFinalSpeed: return "final_speed";
    case Quantity::kPeakContactForce: return "peak_contact_force";
  }
  return "?";
}

BatchParseResult ParseBatchFile(const std::string& text, const std::string& file_name) {
  BatchParseResult result;
  const std::optional<xml::Document> doc = xml::Document::Read(
      text, file_name, "batch", xml::Dtd{"batch.dtd", kBatchDtdText}, &result.diagnostics);
  if (!doc || !result.diagnostics.empty()) return result;
  result.batch = Reader(file_name, &result.diagnostics).Read(doc->root());
  return result;
}

BatchParseResult LoadBatchFile(const std::string& path) {
  std::string text;
  try {
    text = ReadBoundedFile(path, xml::kMaxDocumentBytes, "batch files");
  } catch (const FileReadError& e) {
    BatchParseResult result;
    result.diagnostics.Add(
        path, 0, "", e.cannot_open() ? std::string("cannot read the batch file: ") + e.what() : e.what());
    return result;
  }
  return ParseBatchFile(text, path);
}

}  // namespace simpartner::batch
