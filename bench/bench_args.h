// The command line of every bench program, in one place: --help prints the
// usage, an option's value is checked before anything runs, and a
// misspelled option is refused with the nearest name (a bench that took it
// for a world file would start a sim on it and wait).
#pragma once

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "simpartner/edit_distance.h"

namespace simpartner::bench {

enum class ValueKind { kNone, kText, kNumber, kInteger };

struct BenchOption {
  std::string name;        // with "--"
  ValueKind kind;          // kNone: a switch
  std::string value_name;  // "S", "URL": how the usage names the value
  std::string help;        // with the default
};

struct BenchUsage {
  std::string program;      // "latency_bench"
  std::string positional;   // "[world.xml]", "[world.xml ...]"; empty = none taken
  int max_positional = 0;   // -1 = any number
  std::string description;  // what it runs and prints
  std::vector<BenchOption> options;
};

// A command line the bench cannot run with; what() names the argument.
class BenchArgsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BenchArgs {
  bool help = false;
  std::map<std::string, std::vector<std::string>> given;  // option -> values, in order
  std::vector<std::string> positional;

  bool Has(const std::string& option) const { return given.count(option) > 0; }
  // The last value given, or fallback.
  std::string Text(const std::string& option, const std::string& fallback) const {
    const auto it = given.find(option);
    return it == given.end() ? fallback : it->second.back();
  }
  std::vector<std::string> All(const std::string& option) const {
    const auto it = given.find(option);
    return it == given.end() ? std::vector<std::string>{} : it->second;
  }
  // Values were checked by ParseBenchArgs.
  double Number(const std::string& option, double fallback) const {
    return Has(option) ? std::strtod(Text(option, "").c_str(), nullptr) : fallback;
  }
  long Integer(const std::string& option, long fallback) const {
    return Has(option) ? std::strtol(Text(option, "").c_str(), nullptr, 10) : fallback;
  }
};

inline std::string FormatBenchUsage(const BenchUsage& usage) {
  std::string out = "Usage: " + usage.program + " [options]";
  if (!usage.positional.empty()) out += " " + usage.positional;
  out += "\n\n" + usage.description + "\n\nOptions:\n";
  auto line = [&out](const std::string& left, const std::string& help) {
    std::string padded = "  " + left;
    if (padded.size() < 26) padded.resize(26, ' ');
    else padded += "  ";
    out += padded + help + "\n";
  };
  for (const BenchOption& o : usage.options)
    line(o.name + (o.kind == ValueKind::kNone ? "" : " " + o.value_name), o.help);
  line("--help", "show this text and exit");
  return out;
}

// Throws BenchArgsError for an unknown option (with the nearest known one),
// a missing or malformed value, or too many positional arguments.
inline BenchArgs ParseBenchArgs(int argc, const char* const* argv, const BenchUsage& usage) {
  BenchArgs args;
  auto find = [&usage](const std::string& name) -> const BenchOption* {
    for (const BenchOption& o : usage.options)
      if (o.name == name) return &o;
    return nullptr;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const std::string where = "argument " + std::to_string(i) + " '" + arg + "'";
    if (arg == "--help" || arg == "-h") {
      args.help = true;
      continue;
    }
    if (arg.empty() || arg[0] != '-') {
      if (usage.max_positional >= 0 &&
          static_cast<int>(args.positional.size()) >= usage.max_positional)
        throw BenchArgsError(where + ": " +
                             (usage.positional.empty() ? std::string("takes no arguments")
                                                       : "one too many (it takes " + usage.positional + ")"));
      args.positional.push_back(arg);
      continue;
    }
    const size_t eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const BenchOption* option = find(name);
    if (option == nullptr) {
      std::string nearest, known;
      size_t best = 4;  // at most 3 edits away
      for (const BenchOption& o : usage.options) {
        known += o.name + " ";
        const size_t d = EditDistance(name, o.name);
        if (d < best) best = d, nearest = o.name;
      }
      if (EditDistance(name, "--help") < best) nearest = "--help";
      throw BenchArgsError(where + ": unknown option" +
                           (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") +
                           "; it takes: " + known + "--help");
    }
    if (option->kind == ValueKind::kNone) {
      if (eq != std::string::npos) throw BenchArgsError(where + ": " + name + " takes no value");
      args.given[name].push_back("");
      continue;
    }
    std::string value;
    if (eq != std::string::npos) value = arg.substr(eq + 1);
    else if (i + 1 < argc) value = argv[++i];
    else throw BenchArgsError(where + ": needs a value (" + name + " " + option->value_name + ")");
    if (option->kind == ValueKind::kNumber || option->kind == ValueKind::kInteger) {
      char* end = nullptr;
      const double number = option->kind == ValueKind::kNumber
                                ? std::strtod(value.c_str(), &end)
                                : static_cast<double>(std::strtol(value.c_str(), &end, 10));
      if (value.empty() || *end != '\0' || !std::isfinite(number))
        throw BenchArgsError(name + " '" + value + "': not " +
                             (option->kind == ValueKind::kNumber ? "a number" : "a whole number"));
    }
    args.given[name].push_back(value);
  }
  return args;
}

// For main(): --help prints the usage and exits 0; a bad command line
// prints why and exits 2, before the bench starts anything.
inline BenchArgs ParseBenchArgsOrExit(int argc, const char* const* argv, const BenchUsage& usage) {
  try {
    BenchArgs args = ParseBenchArgs(argc, argv, usage);
    if (args.help) {
      std::cout << FormatBenchUsage(usage);
      std::exit(0);
    }
    return args;
  } catch (const BenchArgsError& e) {
    std::cerr << usage.program << ": " << e.what() << "\n(" << usage.program
              << " --help lists the options)\n";
    std::exit(2);
  }
}

}  // namespace simpartner::bench
