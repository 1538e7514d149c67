// The one command-line parser of every SimPartner program and bench
// (docs/command_line.md). A program describes what it takes in a
// CommandLineSpec: options with a kind (switch, text, number, integer), a
// value name and help; positional arguments with counts; optionally
// commands with their own arguments; and, for a program that reads
// parameters.txt, the parameter sections it uses. Every program then gets
// the same --help layout, the same messages for a bad command line (exit
// status 2), and a did-you-mean for a misspelled option, command or key.
#pragma once

#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/parameters.h"

namespace simpartner {

// The exit status of every program for a command line it cannot run with.
inline constexpr int kUsageExitStatus = 2;

enum class OptionKind {
  kSwitch,   // --name
  kText,     // --name VALUE or --name=VALUE
  kNumber,   // a finite number (strtod)
  kInteger,  // a whole number
};

struct Option {
  std::string name;  // without "--"
  OptionKind kind = OptionKind::kSwitch;
  std::string value_name;  // how --help names the value: "S", "URL", "FILE"
  std::string help;        // what it does, with its default
  char short_name = 0;     // -o for --out; 0 = none
  std::vector<std::string> choices = {};  // kText: the only values it takes (empty: any)
  // kNumber, kInteger: the allowed range; min itself is refused when
  // min_excluded ("above 0").
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_excluded = false;

  // Copies with one more property, to write a table of options readably.
  Option Short(char letter) const;
  Option Choices(std::vector<std::string> values) const;
  Option Range(double low, double high) const;  // low <= value <= high
  Option Above(double low, double high = std::numeric_limits<double>::infinity()) const;
};

Option Switch(std::string name, std::string help);
Option Text(std::string name, std::string value_name, std::string help);
Option Number(std::string name, std::string value_name, std::string help);
Option Integer(std::string name, std::string value_name, std::string help);

inline constexpr int kAnyCount = -1;

// A positional argument taken min to max times (max kAnyCount: any).
struct Positional {
  std::string name;  // "SIM", "FILE.xml", "on|off"
  int min = 1;
  int max = 1;
  std::vector<std::string> choices = {};  // the only values it takes (empty: any)
};

// A command of a program that has them (simpartner-cmd set, simpartner-query
// plot): the first positional argument names it.
struct Command {
  std::string name;
  std::vector<Positional> positionals = {};
  std::string help = "";
  // The program's options that go with this command. An option that no
  // command names goes with every command.
  std::vector<std::string> options = {};
  std::vector<std::string> required = {};  // of those, the ones it cannot do without
};

// A program that reads parameters.txt: it takes --params FILE, --lcm-url URL
// (--lcmUrl=URL), --print-parameters and any key as --key=value, and its
// --help lists the keys of these sections.
struct ParameterUse {
  std::vector<std::string> sections;  // of parameter_sections; empty: all
  // Without --params FILE: ./parameters.txt or the shipped one (true), or
  // no file at all, only the defaults and the --key=value given (false).
  bool default_file = true;
};

struct CommandLineSpec {
  std::string program;  // "simpartner-sim"
  std::string summary;  // what the program does; lines longer than the help are wrapped
  std::vector<Option> options;
  std::vector<Positional> positionals;  // without commands
  std::vector<Command> commands;        // empty: the program has none
  std::vector<std::string> required;    // options the program cannot do without
  std::optional<ParameterUse> parameters;
  std::string epilogue;  // after the options: names used above, exit statuses
};

// A command line the program cannot run with; what() says why, naming the
// argument, and the nearest known name for a misspelling.
class CommandLineError : public Error {
 public:
  using Error::Error;
};

// What a command line asked for, checked against its spec: the values have
// their kinds and ranges, the positional arguments their counts.
class CommandLine {
 public:
  bool help() const { return help_; }
  bool print_parameters() const { return print_parameters_; }
  const std::string& command() const { return command_; }  // "" without commands
  // The positional arguments (after the command), in order.
  const std::vector<std::string>& positional() const { return positional_; }
  const ParameterSources& parameter_sources() const { return parameter_sources_; }

  // By option name without "--"; a name the spec does not declare is a
  // programming error (std::invalid_argument).
  bool Has(const std::string& option) const;
  // The last value given, or fallback.
  std::string Text(const std::string& option, const std::string& fallback = "") const;
  std::vector<std::string> All(const std::string& option) const;  // every value, in order
  double Number(const std::string& option, double fallback) const;
  long long Integer(const std::string& option, long long fallback) const;

 private:
  friend CommandLine ParseCommandLine(const CommandLineSpec&, const std::vector<std::string>&);
  const std::string* Last(const std::string& option) const;

  bool help_ = false;
  bool print_parameters_ = false;
  std::string command_;
  std::vector<std::string> positional_;
  std::vector<std::pair<std::string, std::string>> given_;  // option, value ("" for a switch)
  std::vector<std::string> declared_;
  ParameterSources parameter_sources_;
};

// Parses args (without the program name). --help or -h anywhere asks for
// the help and nothing else is checked. Throws CommandLineError for the
// first problem; std::invalid_argument for a spec that names an option it
// does not declare.
CommandLine ParseCommandLine(const CommandLineSpec& spec, const std::vector<std::string>& args);

// The --help text: usage line, summary, commands, options, epilogue, and
// the parameter keys of the sections the program reads.
std::string FormatHelp(const CommandLineSpec& spec);

// Writes "PROGRAM: message" and where the usage is to err; returns
// kUsageExitStatus. For a program's own checks after parsing too.
int ReportUsageError(const CommandLineSpec& spec, const std::string& message, std::ostream& err);

// The front of every program's Run(): parses args into *command_line and
// returns nothing when the program goes on; returns the exit status when it
// is done: 0 after writing the help to out, kUsageExitStatus after writing
// why the command line is refused to err.
std::optional<int> ReadCommandLine(const CommandLineSpec& spec, const std::vector<std::string>& args,
                                   std::ostream& out, std::ostream& err, CommandLine* command_line);

// --print-parameters: writes params to out and returns true, for the
// program to exit 0; false when not asked.
bool PrintParametersIfAsked(const CommandLine& command_line, const Parameters& params,
                            std::ostream& out);

}  // namespace simpartner
