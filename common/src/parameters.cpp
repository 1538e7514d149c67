#include "simpartner/parameters.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "simpartner/bounded_file.h"
#include "simpartner/data_paths.h"
#include "simpartner/edit_distance.h"
#include "simpartner/text.h"

namespace simpartner {
namespace {

constexpr const char* kCommandLine = "command line";

// One key of Parameters: how to set it from text and how to show it.
struct Entry {
  std::string key;
  std::string type;     // "bool", "int", "real", "string", "path", "choice"
  std::string range;    // human-readable allowed values
  std::string doc;
  std::string section;
  // Returns "" on success or the reason the text is not acceptable.
  std::function<std::string(const std::string& text, const std::string& base_dir)>
      set;
  std::function<std::string()> get;
};

// Visitor that turns Parameters::Visit into a table of Entries bound to one
// Parameters object.
class EntryBinder {
 public:
  std::vector<Entry> entries;

  void Section(const char* title) { section_ = title; }

  void Bool(const char* key, bool& field, const char* doc) {
    Add(key, "bool", "0 or 1 (also true/false, yes/no, on/off)", doc,
        [&field](const std::string& text, const std::string&) -> std::string {
          static const std::map<std::string, bool> kWords = {
              {"0", false}, {"1", true},     {"false", false}, {"true", true},
              {"no", false}, {"yes", true},  {"off", false},   {"on", true}};
          const auto it = kWords.find(text);
          if (it == kWords.end()) return "is not a boolean";
          field = it->second;
          return "";
        },
        [&field] { return std::string(field ? "1" : "0"); });
  }

  void Int(const char* key, int& field, long long min, long long max,
           const char* doc) {
    const std::string range =
        "integer " + std::to_string(min) + " to " + std::to_string(max);
    Add(key, "int", range, doc,
        [&field, min, max, range](const std::string& text,
                                  const std::string&) -> std::string {
          errno = 0;
          char* end = nullptr;
          const long long value = std::strtoll(text.c_str(), &end, 10);
          if (text.empty() || end == text.c_str() || *end != '\0')
            return "is not an integer";
          if (errno == ERANGE || value < min || value > max)
            return "is out of range (allowed: " + range + ")";
          field = static_cast<int>(value);
          return "";
        },
        [&field] { return std::to_string(field); });
  }

  void Double(const char* key, double& field, double min, double max,
              const char* doc) {
    const std::string range = "number " + ShortestNumber(min) + " to " + ShortestNumber(max);
    Add(key, "real", range, doc,
        [&field, min, max, range](const std::string& text,
                                  const std::string&) -> std::string {
          errno = 0;
          char* end = nullptr;
          const double value = std::strtod(text.c_str(), &end);
          if (text.empty() || end == text.c_str() || *end != '\0')
            return "is not a number";
          if (!std::isfinite(value)) return "is not a finite number";
          if (value < min || value > max)
            return "is out of range (allowed: " + range + ")";
          field = value;
          return "";
        },
        [&field] { return ShortestNumber(field); });
  }

  void String(const char* key, std::string& field, const char* doc) {
    Add(key, "string", "any text", doc,
        [&field](const std::string& text, const std::string&) -> std::string {
          field = text;
          return "";
        },
        [&field] { return field; });
  }

  void Path(const char* key, std::string& field, const char* doc) {
    Add(key, "path", "file path", doc,
        [&field](const std::string& text, const std::string& base_dir) -> std::string {
          if (text.empty()) return "is empty (a file path is needed)";
          const std::filesystem::path path(text);
          field = (path.is_relative() && !base_dir.empty())
                      ? (std::filesystem::path(base_dir) / path).lexically_normal().string()
                      : text;
          return "";
        },
        [&field] { return field; });
  }

  void Choice(const char* key, std::string& field,
              const std::vector<std::string>& choices, const char* doc) {
    std::string range = "one of";
    for (const std::string& c : choices) range += " " + c;
    Add(key, "choice", range, doc,
        [&field, choices, range](const std::string& text,
                                 const std::string&) -> std::string {
          for (const std::string& c : choices) {
            if (c == text) {
              field = text;
              return "";
            }
          }
          return "is not allowed (" + range + ")";
        },
        [&field] { return field; });
  }

 private:
  void Add(const char* key, const char* type, std::string range,
           const char* doc, decltype(Entry::set) set, decltype(Entry::get) get) {
    entries.push_back(Entry{key, type, std::move(range), doc, section_,
                            std::move(set), std::move(get)});
  }
  std::string section_;
};

std::vector<Entry> BindEntries(Parameters* params) {
  EntryBinder binder;
  params->Visit(binder);
  return std::move(binder.entries);
}

const Entry* FindEntry(const std::vector<Entry>& entries, const std::string& key) {
  for (const Entry& e : entries)
    if (e.key == key) return &e;
  return nullptr;
}

// Sets key to value; false (and a diagnostic) when it could not.
bool SetValue(const std::vector<Entry>& entries, const std::string& key,
              const std::string& value, const std::string& base_dir,
              const ParameterOrigin& origin, DiagnosticList* diagnostics) {
  const Entry* entry = FindEntry(entries, key);
  if (entry == nullptr) {
    std::string message = "unknown key '" + key + "'";
    std::vector<std::string> keys;
    for (const Entry& e : entries) keys.push_back(e.key);
    const std::string hint = NearestName(key, keys);
    if (!hint.empty()) message += " (did you mean '" + hint + "'?)";
    diagnostics->Add(origin.file, origin.line, key, message);
    return false;
  }
  const std::string problem = entry->set(value, base_dir);
  if (problem.empty()) return true;
  diagnostics->Add(origin.file, origin.line, key, "value '" + value + "' " + problem);
  return false;
}

std::string DirectoryOf(const std::string& file) {
  const std::filesystem::path parent = std::filesystem::path(file).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

// Where each key was set (file line or command line), for the checks
// between keys.
using KeyOrigins = std::map<std::string, ParameterOrigin>;

// globalERP and globalCFM are the per-step law: set while jointStiffness
// gives the joints' law, they would be ignored, so they are refused.
void CheckJointLaw(const Parameters& params, const KeyOrigins& set,
                   DiagnosticList* diagnostics) {
  if (params.jointStiffness <= 0.0) return;
  for (const char* key : {"globalERP", "globalCFM"}) {
    const auto it = set.find(key);
    if (it == set.end()) continue;
    diagnostics->Add(it->second.file, it->second.line, key,
                     std::string(key) +
                         " applies only with jointStiffness=0: the joints' ERP and CFM come "
                         "from jointStiffness and jointDamping (the same spring at any step "
                         "size); set jointStiffness=0 for the per-step law");
  }
}

void ParseText(const std::string& text, const std::string& file_name, Parameters* params,
               DiagnosticList* diagnostics, KeyOrigins* set);

}  // namespace

void ParseParametersText(const std::string& text, const std::string& file_name,
                         Parameters* params, DiagnosticList* diagnostics) {
  ParseText(text, file_name, params, diagnostics, nullptr);
}

namespace {

void ParseText(const std::string& text, const std::string& file_name, Parameters* params,
               DiagnosticList* diagnostics, KeyOrigins* set) {
  const std::vector<Entry> entries = BindEntries(params);
  const std::string base_dir = DirectoryOf(file_name);
  std::map<std::string, int> line_of_key;
  // Editors on Windows start UTF-8 files with a byte order mark; it is not
  // part of the first key.
  constexpr char kUtf8Bom[] = "\xEF\xBB\xBF";
  const bool has_bom = text.compare(0, 3, kUtf8Bom) == 0;
  std::istringstream in(has_bom ? text.substr(3) : text);
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const size_t hash = raw.find('#');
    const std::string line = Trim(hash == std::string::npos ? raw : raw.substr(0, hash));
    if (line.empty()) continue;
    const size_t eq = line.find('=');
    if (eq == std::string::npos) {
      diagnostics->Add(file_name, line_number, "",
                       "expected key=value, found '" + line + "'");
      continue;
    }
    const std::string key = Trim(line.substr(0, eq));
    const std::string value = Trim(line.substr(eq + 1));
    if (key.empty()) {
      diagnostics->Add(file_name, line_number, "", "missing key before '='");
      continue;
    }
    const auto previous = line_of_key.find(key);
    if (previous != line_of_key.end()) {
      diagnostics->Add(file_name, line_number, key,
                       "set twice (first at line " +
                           std::to_string(previous->second) + ")");
      continue;
    }
    line_of_key[key] = line_number;
    const ParameterOrigin origin{file_name, line_number};
    if (SetValue(entries, key, value, base_dir, origin, diagnostics) && set) (*set)[key] = origin;
  }
}

}  // namespace

Parameters LoadParameters(const ParameterSources& sources) {
  Parameters params;
  DiagnosticList diagnostics;
  KeyOrigins set;
  std::string file = sources.file_given ? sources.file : std::string();
  if (!sources.file_given && sources.default_file) {
    // The default file: ./parameters.txt, else the shipped one; none is fine.
    try {
      file = FindDataFile(kDefaultParametersFile, "parameters");
    } catch (const DataFileNotFound&) {
    }
  }
  if (!file.empty()) {
    try {
      ParseText(ReadBoundedFile(file, kMaxSettingsFileBytes, "parameters files"), file, &params,
                &diagnostics, &set);
    } catch (const FileReadError& e) {
      // The default file is optional: one that cannot be opened is skipped.
      if (!e.cannot_open())
        diagnostics.Add(file, 0, "", e.what());
      else if (sources.file_given)
        diagnostics.Add(file, 0, "", std::string("cannot open parameters file: ") + e.what());
    }
  }
  const std::vector<Entry> entries = BindEntries(&params);
  for (const auto& [key, value] : sources.overrides) {
    const ParameterOrigin origin{kCommandLine, 0};
    if (SetValue(entries, key, value, "", origin, &diagnostics)) set[key] = origin;
  }
  CheckJointLaw(params, set, &diagnostics);
  if (!diagnostics.empty()) throw ConfigError(diagnostics);
  return params;
}

std::string FormatParameters(const Parameters& params) {
  Parameters copy = params;
  std::string out;
  for (const Entry& e : BindEntries(&copy)) out += e.key + "=" + e.get() + "\n";
  return out;
}

std::vector<std::string> ParameterKeys() {
  Parameters params;
  std::vector<std::string> keys;
  for (const Entry& e : BindEntries(&params)) keys.push_back(e.key);
  return keys;
}

std::string DescribeParameters(const std::vector<std::string>& sections) {
  Parameters params;
  const std::vector<Entry> entries = BindEntries(&params);
  for (const std::string& wanted : sections) {
    if (std::none_of(entries.begin(), entries.end(),
                     [&wanted](const Entry& e) { return e.section == wanted; }))
      throw std::invalid_argument("DescribeParameters: no parameter section '" + wanted + "'");
  }
  std::string out;
  std::string section;
  for (const Entry& e : entries) {
    if (!sections.empty() &&
        std::find(sections.begin(), sections.end(), e.section) == sections.end())
      continue;
    if (e.section != section) {
      section = e.section;
      out += "\n  " + section + ":\n";
    }
    out += "    " + e.key + "=" + e.get() + "\n        " + e.doc + " [" + e.range + "]\n";
  }
  return out;
}

}  // namespace simpartner
