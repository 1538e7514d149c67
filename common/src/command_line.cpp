#include "simpartner/command_line.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <stdexcept>

#include "simpartner/edit_distance.h"
#include "simpartner/text.h"

namespace simpartner {
namespace {

constexpr size_t kHelpWidth = 100;   // columns of --help
constexpr size_t kHelpColumn = 28;   // where an option's help starts

// The options every program that reads parameters takes besides its own.
std::vector<Option> ParameterOptions(const ParameterUse& use) {
  return {Text("params", "FILE",
               use.default_file ? "parameters file (default: ./parameters.txt, else the shipped "
                                  "one, found like any data file; see SIMPARTNER_DATA in docs/install.md)"
                                : "parameters file (default: none, the built-in defaults)"),
          Text("lcm-url", "URL", std::string("LCM URL, the same as --lcmUrl=URL (default ") +
                                     kDefaultLcmUrl + ")")};
}
Option PrintParametersOption() {
  return Switch("print-parameters",
                "print the effective parameters (file + overrides) as key=value and exit");
}
Option HelpOption() { return Switch("help", "show this text and exit").Short('h'); }

// Every option the program takes, in the order --help lists them.
std::vector<Option> AllOptions(const CommandLineSpec& spec) {
  std::vector<Option> all =
      spec.parameters ? ParameterOptions(*spec.parameters) : std::vector<Option>{};
  all.insert(all.end(), spec.options.begin(), spec.options.end());
  if (spec.parameters) all.push_back(PrintParametersOption());
  all.push_back(HelpOption());
  return all;
}

const Option* FindLong(const std::vector<Option>& options, const std::string& name) {
  for (const Option& o : options)
    if (o.name == name) return &o;
  return nullptr;
}

const Option* FindShort(const std::vector<Option>& options, char letter) {
  for (const Option& o : options)
    if (o.short_name != 0 && o.short_name == letter) return &o;
  return nullptr;
}

const Command* FindCommand(const CommandLineSpec& spec, const std::string& name) {
  for (const Command& c : spec.commands)
    if (c.name == name) return &c;
  return nullptr;
}

bool Contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// "a", "a or b", "a, b or c".
std::string JoinOr(const std::vector<std::string>& items) {
  std::string out;
  for (size_t k = 0; k < items.size(); ++k)
    out += (k == 0 ? "" : k + 1 == items.size() ? " or " : ", ") + items[k];
  return out;
}

std::string Join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (size_t k = 0; k < items.size(); ++k) out += (k == 0 ? "" : separator) + items[k];
  return out;
}

// A spec that names an option it does not declare is a bug of the program.
void CheckSpec(const CommandLineSpec& spec, const std::vector<Option>& options) {
  // Commands and required lists name the program's own options.
  auto own = [&](const std::string& name, const std::string& where) {
    if (FindLong(spec.options, name) == nullptr)
      throw std::invalid_argument(spec.program + ": " + where + " names undeclared option '" +
                                  name + "'");
  };
  for (size_t i = 0; i < options.size(); ++i)
    for (size_t j = i + 1; j < options.size(); ++j)
      if (options[i].name == options[j].name)
        throw std::invalid_argument(spec.program + ": option '" + options[i].name +
                                    "' declared twice");
  for (const std::string& name : spec.required) own(name, "the program");
  for (const Command& c : spec.commands) {
    for (const std::string& name : c.options) own(name, "command '" + c.name + "'");
    for (const std::string& name : c.required) own(name, "command '" + c.name + "'");
  }
}

std::string RangeText(const Option& o) {
  auto number = [](double v) { return FormatNumber(v, 12); };
  const bool low = std::isfinite(o.min), high = std::isfinite(o.max);
  if (low && o.min_excluded)
    return " above " + number(o.min) + (high ? " and at most " + number(o.max) : "");
  if (low && high) return " from " + number(o.min) + " to " + number(o.max);
  if (low) return " of " + number(o.min) + " or more";
  if (high) return " of " + number(o.max) + " or less";
  return "";
}

// "value 'x' is not a, b or c", with the nearest when x is a misspelling.
std::string NotAChoice(const std::string& text, const std::vector<std::string>& choices) {
  const std::string nearest = NearestName(text, choices);
  return "value '" + text + "' is not " + JoinOr(choices) +
         (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)");
}

// Why text is no value of option o, or "" when it is one.
std::string ValueProblem(const Option& o, const std::string& text) {
  if (o.kind == OptionKind::kText) {
    if (o.choices.empty() || Contains(o.choices, text)) return "";
    return NotAChoice(text, o.choices);
  }
  errno = 0;
  char* end = nullptr;
  const double value = o.kind == OptionKind::kNumber
                           ? std::strtod(text.c_str(), &end)
                           : static_cast<double>(std::strtoll(text.c_str(), &end, 10));
  const bool read = !text.empty() && *end == '\0' && errno != ERANGE && std::isfinite(value);
  const bool in_range = value <= o.max && (o.min_excluded ? value > o.min : value >= o.min);
  if (read && in_range) return "";
  return "value '" + text + "' is not " +
         (o.kind == OptionKind::kNumber ? "a number" : "a whole number") + RangeText(o);
}

std::string Dashed(const Option& o) { return "--" + o.name; }

std::string ValueName(const Option& o) {
  if (!o.value_name.empty()) return o.value_name;
  return o.choices.empty() ? "VALUE" : Join(o.choices, "|");
}

// "--name VALUE", or "--name" for a switch.
std::string OptionUsage(const Option& o) {
  return Dashed(o) + (o.kind == OptionKind::kSwitch ? "" : " " + ValueName(o));
}

// The nearest of the program's options (and, for a program that reads
// parameters, keys) to a misspelled one, as the user should have typed it.
std::string NearestOption(const CommandLineSpec& spec, const std::vector<Option>& options,
                          const std::string& name, const std::string& value) {
  std::vector<std::string> names;
  for (const Option& o : options) names.push_back(o.name);
  if (spec.parameters)
    for (const std::string& key : ParameterKeys()) names.push_back(key);
  const std::string nearest = NearestName(name, names);
  if (nearest.empty()) return "";
  if (FindLong(options, nearest) != nullptr) return "--" + nearest;
  return "--" + nearest + "=" + (value.empty() ? "VALUE" : value);
}

[[noreturn]] void UnknownOption(const CommandLineSpec& spec, const std::vector<Option>& options,
                                const std::string& argument, const std::string& name,
                                const std::string& value) {
  const std::string nearest = NearestOption(spec, options, name, value);
  std::string message = "unknown option '" + argument + "'";
  if (!nearest.empty()) throw CommandLineError(message + " (did you mean '" + nearest + "'?)");
  std::vector<std::string> known;
  for (const Option& o : options) known.push_back(Dashed(o));
  throw CommandLineError(message + "; it takes: " + Join(known, " ") +
                         (spec.parameters ? " and any parameter as --key=value" : ""));
}

// The positional usage: NAME, [NAME], NAME ..., [NAME ...].
std::string PositionalUsage(const Positional& p) {
  if (p.max == 1) return p.min >= 1 ? p.name : "[" + p.name + "]";
  return p.min >= 1 ? p.name + " ..." : "[" + p.name + " ...]";
}

std::string PositionalsUsage(const std::vector<Positional>& positionals) {
  std::vector<std::string> parts;
  for (const Positional& p : positionals) parts.push_back(PositionalUsage(p));
  return Join(parts, " ");
}

// Checks the count of words against positionals and the choices of each;
// who takes them: a command, or "" for the program.
void CheckPositionals(const std::vector<Positional>& positionals, const std::vector<std::string>& words,
                      const std::string& who) {
  size_t next = 0;  // the first word not yet given to a positional
  size_t spare = words.size();
  for (const Positional& p : positionals) spare -= std::min<size_t>(spare, static_cast<size_t>(p.min));
  for (const Positional& p : positionals) {
    if (next + static_cast<size_t>(p.min) > words.size())
      throw CommandLineError(who.empty() ? "missing " + p.name : who + " needs " + p.name);
    size_t take = static_cast<size_t>(p.min);
    const size_t room = p.max == kAnyCount ? spare : static_cast<size_t>(p.max - p.min);
    const size_t extra = std::min(room, spare);
    take += extra;
    spare -= extra;
    for (size_t k = next; k < next + take; ++k)
      if (!p.choices.empty() && !Contains(p.choices, words[k]))
        throw CommandLineError((who.empty() ? p.name : who) + ": " + NotAChoice(words[k], p.choices));
    next += take;
  }
  if (next < words.size()) {
    const std::string takes = positionals.empty() ? "no arguments" : PositionalsUsage(positionals);
    throw CommandLineError("unexpected argument '" + words[next] + "' (" +
                           (who.empty() ? "it" : who) + " takes " + takes + ")");
  }
}

// Whether an argument is a positional one: anything but -x and --x; "-",
// and negative numbers like -1 or -0.5,0.5, are positional.
bool IsPositional(const std::string& argument) {
  if (argument.size() < 2 || argument[0] != '-') return true;
  return std::isdigit(static_cast<unsigned char>(argument[1])) != 0 || argument[1] == '.';
}

std::string RequiredUsage(const CommandLineSpec& spec, const std::vector<std::string>& required) {
  std::string out;
  for (const std::string& name : required) {
    const Option* o = FindLong(spec.options, name);
    out += " " + (o->short_name != 0 ? "-" + std::string(1, o->short_name) + " " + ValueName(*o)
                                      : OptionUsage(*o));
  }
  return out;
}

// Appends text to out, whose last line is `column` wide, wrapping at
// spaces before kHelpWidth; continuation lines start with `indent` spaces.
void AppendWrapped(std::string* out, const std::string& text, size_t column, size_t indent) {
  size_t start = 0;
  while (column + (text.size() - start) > kHelpWidth && kHelpWidth > column + 20) {
    const size_t room = kHelpWidth - column;
    size_t cut = text.rfind(' ', start + room);
    if (cut == std::string::npos || cut <= start) cut = text.find(' ', start + room);
    if (cut == std::string::npos) break;
    *out += text.substr(start, cut - start) + "\n" + std::string(indent, ' ');
    start = cut + 1;
    column = indent;
  }
  *out += text.substr(start);
}

// Each line of text, wrapped, continuation lines indented like the line.
std::string WrapParagraphs(const std::string& text) {
  std::string out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    const size_t indent = std::min(line.find_first_not_of(' '), line.size());
    AppendWrapped(&out, line, 0, indent);
    if (end < text.size()) out += "\n";
    start = end + 1;
  }
  return out;
}

// "  left      help", help wrapped at kHelpColumn; lines of help after a
// '\n' start at kHelpColumn too.
void AppendEntry(std::string* out, const std::string& left, const std::string& help) {
  std::string line = "  " + left;
  if (line.size() < kHelpColumn) line.resize(kHelpColumn, ' ');
  else line += "  ";
  *out += line;
  size_t column = line.size();
  size_t start = 0;
  while (start <= help.size()) {
    size_t end = help.find('\n', start);
    if (end == std::string::npos) end = help.size();
    AppendWrapped(out, help.substr(start, end - start), column, kHelpColumn);
    *out += "\n";
    if (end < help.size()) *out += std::string(kHelpColumn, ' ');
    column = kHelpColumn;
    start = end + 1;
  }
}

// The commands an option goes with ("" = every command).
std::vector<std::string> CommandsOf(const CommandLineSpec& spec, const std::string& option) {
  std::vector<std::string> names;
  for (const Command& c : spec.commands)
    if (Contains(c.options, option)) names.push_back(c.name);
  return names;
}

std::string UsageLine(const CommandLineSpec& spec) {
  std::string out = spec.program + " [options]" + RequiredUsage(spec, spec.required);
  if (!spec.commands.empty()) out += " COMMAND [ARGS]";
  else if (!spec.positionals.empty()) out += " " + PositionalsUsage(spec.positionals);
  if (spec.parameters) out += " [--key=value ...]";
  return out;
}

// The words of a command line after its options: the command (if the
// program has commands) and the positional arguments, checked.
void CheckWords(const CommandLineSpec& spec, const std::vector<std::string>& words,
                CommandLine* result, std::string* command, std::vector<std::string>* positional) {
  // --print-parameters answers without the rest: no command or argument is missing.
  const bool only_parameters = result->print_parameters() && words.empty();
  auto check_required = [&](const std::vector<std::string>& required, const std::string& who) {
    for (const std::string& name : required)
      if (!result->Has(name) && !only_parameters)
        throw CommandLineError((who.empty() ? "missing " : who + " needs ") +
                               OptionUsage(*FindLong(spec.options, name)));
  };
  if (spec.commands.empty()) {
    if (!only_parameters) CheckPositionals(spec.positionals, words, "");
    check_required(spec.required, "");
    *positional = words;
    return;
  }
  std::vector<std::string> names;
  for (const Command& c : spec.commands) names.push_back(c.name);
  if (words.empty()) {
    if (only_parameters) return;
    throw CommandLineError("no command given; the commands: " + Join(names, ", "));
  }
  const Command* found = FindCommand(spec, words[0]);
  if (found == nullptr) {
    const std::string nearest = NearestName(words[0], names);
    throw CommandLineError("unknown command '" + words[0] + "'" +
                           (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") +
                           "; the commands: " + Join(names, ", "));
  }
  for (const Option& o : spec.options) {
    const std::vector<std::string> with = CommandsOf(spec, o.name);
    if (result->Has(o.name) && !with.empty() && !Contains(with, found->name))
      throw CommandLineError(Dashed(o) + " goes with " + JoinOr(with) + ", not with " + found->name);
  }
  check_required(spec.required, "");
  check_required(found->required, found->name);
  *command = found->name;
  positional->assign(words.begin() + 1, words.end());
  CheckPositionals(found->positionals, *positional, found->name);
}

}  // namespace

Option Option::Short(char letter) const {
  Option o = *this;
  o.short_name = letter;
  return o;
}
Option Option::Choices(std::vector<std::string> values) const {
  Option o = *this;
  o.choices = std::move(values);
  return o;
}
Option Option::Range(double low, double high) const {
  Option o = *this;
  o.min = low;
  o.max = high;
  o.min_excluded = false;
  return o;
}
Option Option::Above(double low, double high) const {
  Option o = Range(low, high);
  o.min_excluded = true;
  return o;
}

Option Switch(std::string name, std::string help) {
  return Option{std::move(name), OptionKind::kSwitch, "", std::move(help)};
}
Option Text(std::string name, std::string value_name, std::string help) {
  return Option{std::move(name), OptionKind::kText, std::move(value_name), std::move(help)};
}
Option Number(std::string name, std::string value_name, std::string help) {
  return Option{std::move(name), OptionKind::kNumber, std::move(value_name), std::move(help)};
}
Option Integer(std::string name, std::string value_name, std::string help) {
  return Option{std::move(name), OptionKind::kInteger, std::move(value_name), std::move(help)};
}

const std::string* CommandLine::Last(const std::string& option) const {
  if (!Contains(declared_, option))
    throw std::invalid_argument("command line: no option '" + option + "' is declared");
  for (auto it = given_.rbegin(); it != given_.rend(); ++it)
    if (it->first == option) return &it->second;
  return nullptr;
}

bool CommandLine::Has(const std::string& option) const { return Last(option) != nullptr; }

std::string CommandLine::Text(const std::string& option, const std::string& fallback) const {
  const std::string* value = Last(option);
  return value != nullptr ? *value : fallback;
}

std::vector<std::string> CommandLine::All(const std::string& option) const {
  Last(option);  // declared?
  std::vector<std::string> values;
  for (const auto& [name, value] : given_)
    if (name == option) values.push_back(value);
  return values;
}

double CommandLine::Number(const std::string& option, double fallback) const {
  const std::string* value = Last(option);  // checked by ParseCommandLine
  return value != nullptr ? std::strtod(value->c_str(), nullptr) : fallback;
}

long long CommandLine::Integer(const std::string& option, long long fallback) const {
  const std::string* value = Last(option);
  return value != nullptr ? std::strtoll(value->c_str(), nullptr, 10) : fallback;
}

CommandLine ParseCommandLine(const CommandLineSpec& spec, const std::vector<std::string>& args) {
  const std::vector<Option> options = AllOptions(spec);
  CheckSpec(spec, options);
  CommandLine result;
  for (const Option& o : spec.options) result.declared_.push_back(o.name);
  result.parameter_sources_.default_file = !spec.parameters || spec.parameters->default_file;
  for (const std::string& a : args) {
    if (a == "--") break;
    if (a == "--help" || a == "-h") {
      result.help_ = true;
      return result;
    }
  }
  std::vector<std::string> words;  // the command and the positional arguments
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& argument = args[i];
    if (argument == "--") {
      words.insert(words.end(), args.begin() + static_cast<long>(i) + 1, args.end());
      break;
    }
    if (IsPositional(argument)) {
      words.push_back(argument);
      continue;
    }
    const bool is_long = argument[1] == '-';
    const size_t eq = is_long ? argument.find('=') : std::string::npos;
    const std::string name = is_long ? argument.substr(2, eq == std::string::npos ? eq : eq - 2)
                                     : argument.substr(1);
    const bool inline_value = eq != std::string::npos;
    const std::string value = inline_value ? argument.substr(eq + 1) : "";
    const Option* option = is_long ? FindLong(options, name)
                                   : (name.size() == 1 ? FindShort(options, name[0]) : nullptr);
    if (option == nullptr) {
      if (is_long && inline_value && spec.parameters && Contains(ParameterKeys(), name)) {
        result.parameter_sources_.overrides.emplace_back(name, value);
        continue;
      }
      UnknownOption(spec, options, argument, name, value);
    }
    if (option->kind == OptionKind::kSwitch) {
      if (inline_value) throw CommandLineError(Dashed(*option) + " takes no value");
      if (option->name == "print-parameters") result.print_parameters_ = true;
      else result.given_.emplace_back(option->name, "");
      continue;
    }
    std::string text = value;
    if (!inline_value) {
      if (i + 1 >= args.size())
        throw CommandLineError(Dashed(*option) + " needs a value (" + OptionUsage(*option) + ")");
      text = args[++i];
    }
    const std::string problem = ValueProblem(*option, text);
    if (!problem.empty()) throw CommandLineError(Dashed(*option) + ": " + problem);
    if (spec.parameters && option->name == "params") {
      result.parameter_sources_.file = text;
      result.parameter_sources_.file_given = true;
    } else if (spec.parameters && option->name == "lcm-url") {
      result.parameter_sources_.overrides.emplace_back("lcmUrl", text);
    } else {
      result.given_.emplace_back(option->name, text);
    }
  }
  CheckWords(spec, words, &result, &result.command_, &result.positional_);
  return result;
}

std::string FormatHelp(const CommandLineSpec& spec) {
  const std::vector<Option> options = AllOptions(spec);
  CheckSpec(spec, options);
  std::string out = "Usage: " + UsageLine(spec) + "\n";
  if (!spec.summary.empty()) out += "\n" + WrapParagraphs(spec.summary) + "\n";
  if (!spec.commands.empty()) {
    out += "\nCommands:\n";
    for (const Command& c : spec.commands) {
      std::string left = c.name;
      if (!c.positionals.empty()) left += " " + PositionalsUsage(c.positionals);
      left += RequiredUsage(spec, c.required);
      AppendEntry(&out, left, c.help);
    }
  }
  out += "\nOptions:\n";
  for (const Option& o : options) {
    const std::string left =
        (o.short_name != 0 ? "-" + std::string(1, o.short_name) + ", " : "") + OptionUsage(o);
    const std::vector<std::string> with = CommandsOf(spec, o.name);
    AppendEntry(&out, left, (with.empty() ? "" : Join(with, ", ") + ": ") + o.help);
  }
  if (!spec.epilogue.empty()) out += "\n" + WrapParagraphs(spec.epilogue) + "\n";
  if (spec.parameters) {
    out += "\nParameters (key=default, in parameters.txt or as --key=value):\n";
    out += WrapParagraphs(DescribeParameters(spec.parameters->sections));
    if (!spec.parameters->sections.empty())
      out += "\n" + WrapParagraphs("  (parameters.txt is shared by every program: its other keys "
                                   "are for the other programs, accepted and checked here but "
                                   "not used)") + "\n";
  }
  return out;
}

int ReportUsageError(const CommandLineSpec& spec, const std::string& message, std::ostream& err) {
  err << spec.program << ": " << message << "\n"
      << "(" << spec.program << " --help shows the usage)\n";
  return kUsageExitStatus;
}

std::optional<int> ReadCommandLine(const CommandLineSpec& spec, const std::vector<std::string>& args,
                                   std::ostream& out, std::ostream& err, CommandLine* command_line) {
  try {
    *command_line = ParseCommandLine(spec, args);
  } catch (const CommandLineError& e) {
    return ReportUsageError(spec, e.what(), err);
  }
  if (!command_line->help()) return std::nullopt;
  out << FormatHelp(spec);
  return 0;
}

bool PrintParametersIfAsked(const CommandLine& command_line, const Parameters& params,
                            std::ostream& out) {
  if (!command_line.print_parameters()) return false;
  out << FormatParameters(params);
  return true;
}

}  // namespace simpartner
