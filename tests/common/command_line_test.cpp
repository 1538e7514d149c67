// The one command-line parser (common/command_line.h): kinds, counts,
// commands, parameter overrides, the messages a user reads for a bad
// command line and the --help layout every program shares.
#include "simpartner/command_line.h"

#include <gtest/gtest.h>

#include <sstream>

namespace simpartner {
namespace {

CommandLineSpec Bench() {
  CommandLineSpec spec;
  spec.program = "sim_bench";
  spec.summary = "Microseconds per step of each world.";
  spec.options = {Integer("steps", "N", "steps per measurement (default 5000)").Range(1, 1e8),
                  Number("seconds", "S", "how long (default 10)").Above(0),
                  Text("kind", "", "what to send (default refused)").Choices({"refused", "garbage"}),
                  Text("out", "FILE", "write here").Short('o'), Switch("quiet", "no progress")};
  spec.positionals = {Positional{"world.xml", 0, kAnyCount}};
  return spec;
}

// The message a command line is refused with ("" when it is not).
std::string Refusal(const CommandLineSpec& spec, const std::vector<std::string>& args) {
  try {
    ParseCommandLine(spec, args);
  } catch (const CommandLineError& e) {
    return e.what();
  }
  return "";
}

TEST(CommandLineTest, ValuesOfEachKindInBothSpellings) {
  const CommandLine cl = ParseCommandLine(
      Bench(), {"--steps", "200", "--seconds=2.5", "-o", "a.csv", "--out=b.csv", "--quiet", "w.xml"});
  EXPECT_EQ(cl.Integer("steps", 0), 200);
  EXPECT_DOUBLE_EQ(cl.Number("seconds", 0), 2.5);
  EXPECT_EQ(cl.Text("out"), "b.csv");  // the last one given
  EXPECT_EQ(cl.All("out"), (std::vector<std::string>{"a.csv", "b.csv"}));
  EXPECT_TRUE(cl.Has("quiet"));
  EXPECT_FALSE(cl.Has("kind"));
  EXPECT_EQ(cl.Text("kind", "refused"), "refused");
  EXPECT_DOUBLE_EQ(cl.Number("seconds", 7), 2.5);
  EXPECT_EQ(cl.positional(), std::vector<std::string>{"w.xml"});
  EXPECT_FALSE(cl.help());
}

TEST(CommandLineTest, NegativeNumbersAndArgumentsAfterDashDashArePositional) {
  const CommandLine cl = ParseCommandLine(Bench(), {"-1", "-0.5,0.5", "-", "--", "--quiet"});
  EXPECT_EQ(cl.positional(), (std::vector<std::string>{"-1", "-0.5,0.5", "-", "--quiet"}));
  EXPECT_FALSE(cl.Has("quiet"));
  // A value may start with '-'.
  EXPECT_EQ(Refusal(Bench(), {"--seconds", "-1"}), "--seconds: value '-1' is not a number above 0");
}

TEST(CommandLineTest, MisspelledOptionsGetTheNearestName) {
  EXPECT_EQ(Refusal(Bench(), {"--stpes", "10"}), "unknown option '--stpes' (did you mean '--steps'?)");
  EXPECT_EQ(Refusal(Bench(), {"--secnds=3"}), "unknown option '--secnds=3' (did you mean '--seconds'?)");
  EXPECT_EQ(Refusal(Bench(), {"--hepl"}), "unknown option '--hepl' (did you mean '--help'?)");
  EXPECT_EQ(Refusal(Bench(), {"-x"}),
            "unknown option '-x'; it takes: --steps --seconds --kind --out --quiet --help");
  EXPECT_EQ(Refusal(Bench(), {"--zzzzzzzz"}),
            "unknown option '--zzzzzzzz'; it takes: --steps --seconds --kind --out --quiet --help");
}

TEST(CommandLineTest, BadValuesNameTheOptionTheValueAndWhatItTakes) {
  EXPECT_EQ(Refusal(Bench(), {"--steps", "many"}), "--steps: value 'many' is not a whole number from 1 to 100000000");
  EXPECT_EQ(Refusal(Bench(), {"--steps", "1.5"}), "--steps: value '1.5' is not a whole number from 1 to 100000000");
  EXPECT_EQ(Refusal(Bench(), {"--steps=0"}), "--steps: value '0' is not a whole number from 1 to 100000000");
  EXPECT_EQ(Refusal(Bench(), {"--seconds", "0"}), "--seconds: value '0' is not a number above 0");
  EXPECT_EQ(Refusal(Bench(), {"--seconds", "inf"}), "--seconds: value 'inf' is not a number above 0");
  EXPECT_EQ(Refusal(Bench(), {"--kind", "flood"}), "--kind: value 'flood' is not refused or garbage");
  EXPECT_EQ(Refusal(Bench(), {"--kind=refsued"}),
            "--kind: value 'refsued' is not refused or garbage (did you mean 'refused'?)");
  EXPECT_EQ(Refusal(Bench(), {"--steps"}), "--steps needs a value (--steps N)");
  EXPECT_EQ(Refusal(Bench(), {"--quiet=1"}), "--quiet takes no value");
  CommandLineSpec spec = Bench();
  spec.options = {Number("a", "X", "").Range(-89, 89), Number("b", "X", "").Above(0, 65536),
                  Number("c", "X", "").Range(0, std::numeric_limits<double>::infinity()),
                  Number("d", "X", "")};
  EXPECT_EQ(Refusal(spec, {"--a", "95"}), "--a: value '95' is not a number from -89 to 89");
  EXPECT_EQ(Refusal(spec, {"--b", "-3"}), "--b: value '-3' is not a number above 0 and at most 65536");
  EXPECT_EQ(Refusal(spec, {"--c", "-0.5"}), "--c: value '-0.5' is not a number of 0 or more");
  EXPECT_EQ(Refusal(spec, {"--d", "2x"}), "--d: value '2x' is not a number");
  EXPECT_EQ(Refusal(spec, {"--d", ""}), "--d: value '' is not a number");
}

TEST(CommandLineTest, PositionalCounts) {
  CommandLineSpec none = Bench();
  none.positionals = {};
  EXPECT_EQ(Refusal(none, {"world.xml"}), "unexpected argument 'world.xml' (it takes no arguments)");
  CommandLineSpec one = Bench();
  one.positionals = {Positional{"world.xml", 0, 1}};
  EXPECT_EQ(Refusal(one, {"a.xml", "b.xml"}), "unexpected argument 'b.xml' (it takes [world.xml])");
  EXPECT_EQ(Refusal(one, {}), "");
  CommandLineSpec two = Bench();
  two.positionals = {Positional{"IN"}, Positional{"on|off", 1, 1, {"on", "off"}}};
  EXPECT_EQ(Refusal(two, {}), "missing IN");
  EXPECT_EQ(Refusal(two, {"x"}), "missing on|off");
  EXPECT_EQ(Refusal(two, {"x", "maybe"}), "on|off: value 'maybe' is not on or off");
  EXPECT_EQ(ParseCommandLine(two, {"x", "on"}).positional(), (std::vector<std::string>{"x", "on"}));
  CommandLineSpec some = Bench();
  some.positionals = {Positional{"A"}, Positional{"B", 0, 1}, Positional{"C", 1, kAnyCount}};
  EXPECT_EQ(ParseCommandLine(some, {"a", "c"}).positional().size(), 2u);
  EXPECT_EQ(ParseCommandLine(some, {"a", "b", "c", "c"}).positional().size(), 4u);
  EXPECT_EQ(Refusal(some, {"a"}), "missing C");
}

CommandLineSpec Query() {
  CommandLineSpec spec;
  spec.program = "simpartner-query";
  spec.summary = "What is in the database.";
  spec.options = {Text("db-options", "FILE", "MariaDB client option file"),
                  Text("body", "NAME", "only this body"), Integer("keep", "N", "how many to keep"),
                  Switch("force", "even an open one"), Text("out", "FILE", "write here").Short('o')};
  spec.commands = {Command{"list", {}, "the logged simulations"},
                   Command{"poses", {Positional{"SIM"}}, "poses, CSV", {"body", "out"}},
                   Command{"plot", {Positional{"WHAT"}, Positional{"SIM"}}, "a plot", {"body", "out"}},
                   Command{"prune", {}, "remove all but the newest N", {"keep"}, {"keep"}},
                   Command{"compress", {Positional{"on|off", 1, 1, {"on", "off"}}}, "compression"}};
  spec.parameters = ParameterUse{{parameter_sections::kDatabase}};
  spec.epilogue = "SIM is a simulationID from 'list'.";
  return spec;
}

TEST(CommandLineTest, CommandsTakeTheirOwnArgumentsAndOptions) {
  const CommandLine plot =
      ParseCommandLine(Query(), {"--db-options", "r.cnf", "plot", "angle", "last", "-o", "a.png"});
  EXPECT_EQ(plot.command(), "plot");
  EXPECT_EQ(plot.positional(), (std::vector<std::string>{"angle", "last"}));
  EXPECT_EQ(plot.Text("out"), "a.png");
  EXPECT_EQ(plot.Text("db-options"), "r.cnf");  // an option no command names goes with all
  EXPECT_EQ(ParseCommandLine(Query(), {"prune", "--keep", "3"}).Integer("keep", 0), 3);

  EXPECT_EQ(Refusal(Query(), {}), "no command given; the commands: list, poses, plot, prune, compress");
  EXPECT_EQ(Refusal(Query(), {"lst"}),
            "unknown command 'lst' (did you mean 'list'?); the commands: list, poses, plot, prune, "
            "compress");
  EXPECT_EQ(Refusal(Query(), {"list", "--body", "Arm"}), "--body goes with poses or plot, not with list");
  EXPECT_EQ(Refusal(Query(), {"prune"}), "prune needs --keep N");
  EXPECT_EQ(Refusal(Query(), {"list", "7"}), "unexpected argument '7' (list takes no arguments)");
  EXPECT_EQ(Refusal(Query(), {"plot", "angle"}), "plot needs SIM");
  EXPECT_EQ(Refusal(Query(), {"compress"}), "compress needs on|off");
  EXPECT_EQ(Refusal(Query(), {"compress", "maybe"}), "compress: value 'maybe' is not on or off");
  EXPECT_EQ(Refusal(Query(), {"compress", "of"}), "compress: value 'of' is not on or off (did you mean 'off'?)");
  // --print-parameters needs no command.
  EXPECT_TRUE(ParseCommandLine(Query(), {"--print-parameters"}).print_parameters());
}

TEST(CommandLineTest, ParameterProgramsTakeKeysAsOverrides) {
  const CommandLine cl = ParseCommandLine(
      Query(), {"--params", "run.txt", "--dbname=other", "--lcm-url", "memq://", "list"});
  const ParameterSources& sources = cl.parameter_sources();
  EXPECT_EQ(sources.file, "run.txt");
  EXPECT_TRUE(sources.file_given);
  EXPECT_TRUE(sources.default_file);
  using Override = std::pair<std::string, std::string>;
  EXPECT_EQ(sources.overrides, (std::vector<Override>{{"dbname", "other"}, {"lcmUrl", "memq://"}}));
  // A misspelled key, with or without its value; a key is not a switch.
  EXPECT_EQ(Refusal(Query(), {"--dbnme=x", "list"}), "unknown option '--dbnme=x' (did you mean '--dbname=x'?)");
  EXPECT_EQ(Refusal(Query(), {"--dbname", "x", "list"}),
            "unknown option '--dbname' (did you mean '--dbname=VALUE'?)");
  EXPECT_EQ(Refusal(Query(), {"--frce", "list"}), "unknown option '--frce' (did you mean '--force'?)");
  // Far from every name: the options it takes, and that keys go as --key=value.
  const std::string far = Refusal(Query(), {"--zzzzzzzz"});
  EXPECT_NE(far.find("it takes: --params --lcm-url --db-options"), std::string::npos) << far;
  EXPECT_NE(far.find("--print-parameters --help and any parameter as --key=value"), std::string::npos) << far;
  // Without parameters: no --params, no keys.
  EXPECT_EQ(Refusal(Bench(), {"--dbname=x"}),
            "unknown option '--dbname=x'; it takes: --steps --seconds --kind --out --quiet --help");
}

TEST(CommandLineTest, HelpWinsOverEverythingElse) {
  EXPECT_TRUE(ParseCommandLine(Query(), {"--frobnicate", "plot", "-h"}).help());
  EXPECT_TRUE(ParseCommandLine(Bench(), {"--help", "--steps", "x"}).help());
  EXPECT_FALSE(ParseCommandLine(Bench(), {"--", "--help"}).help());
}

TEST(CommandLineTest, HelpLayout) {
  const std::string help = FormatHelp(Query());
  EXPECT_EQ(help.rfind("Usage: simpartner-query [options] COMMAND [ARGS] [--key=value ...]\n\n"
                       "What is in the database.\n\nCommands:\n",
                       0),
            0u)
      << help;
  EXPECT_NE(help.find("\n  list                      the logged simulations\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  plot WHAT SIM             a plot\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  prune --keep N            remove all but the newest N\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  compress on|off           compression\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\nOptions:\n  --params FILE             parameters file"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  --body NAME               poses, plot: only this body\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  -o, --out FILE            poses, plot: write here\n"), std::string::npos) << help;
  EXPECT_NE(help.find("\n  -h, --help                show this text and exit\n\n"
                      "SIM is a simulationID from 'list'.\n\n"
                      "Parameters (key=default, in parameters.txt or as --key=value):\n"),
            std::string::npos)
      << help;
  EXPECT_NE(help.find("\n    dbname=simpartner\n"), std::string::npos) << help;
  EXPECT_EQ(help.find("stepsize="), std::string::npos) << help;

  const std::string bench = FormatHelp(Bench());
  EXPECT_EQ(bench.rfind("Usage: sim_bench [options] [world.xml ...]\n", 0), 0u) << bench;
  EXPECT_NE(bench.find("\n  --kind refused|garbage    what to send"), std::string::npos) << bench;
  EXPECT_EQ(bench.find("--params"), std::string::npos) << bench;
}

TEST(CommandLineTest, LongHelpIsWrappedUnderItsColumn) {
  CommandLineSpec spec = Bench();
  spec.options = {Switch("check", std::string(30, 'a') + " " + std::string(30, 'b') + " " +
                                      std::string(30, 'c') + " " + std::string(30, 'd'))};
  spec.summary = "  " + std::string(60, 'x') + " " + std::string(60, 'y');
  const std::string help = FormatHelp(spec);
  EXPECT_NE(help.find("\n  " + std::string(60, 'x') + "\n  " + std::string(60, 'y') + "\n"),
            std::string::npos)
      << help;
  EXPECT_NE(help.find("\n  --check                   " + std::string(30, 'a') + " " +
                      std::string(30, 'b') + "\n" + std::string(28, ' ') + std::string(30, 'c')),
            std::string::npos)
      << help;
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << line;
}

TEST(CommandLineTest, ReadCommandLineAnswersHelpAndRefusals) {
  std::ostringstream out, err;
  CommandLine cl;
  EXPECT_EQ(ReadCommandLine(Bench(), {"--help"}, out, err, &cl), 0);
  EXPECT_EQ(out.str(), FormatHelp(Bench()));
  EXPECT_EQ(ReadCommandLine(Bench(), {"--cout"}, out, err, &cl), kUsageExitStatus);
  EXPECT_EQ(err.str(), "sim_bench: unknown option '--cout' (did you mean '--out'?)\n"
                       "(sim_bench --help shows the usage)\n");
  EXPECT_EQ(ReadCommandLine(Bench(), {"--steps", "5"}, out, err, &cl), std::nullopt);
  EXPECT_EQ(cl.Integer("steps", 0), 5);
}

TEST(CommandLineTest, ProgrammingErrorsAreNotUsageErrors) {
  const CommandLine cl = ParseCommandLine(Bench(), {});
  EXPECT_THROW(cl.Has("step"), std::invalid_argument);
  CommandLineSpec spec = Query();
  spec.commands[0].options = {"bdy"};
  EXPECT_THROW(ParseCommandLine(spec, {"list"}), std::invalid_argument);
  spec = Bench();
  spec.options.push_back(Switch("quiet", "again"));
  EXPECT_THROW(FormatHelp(spec), std::invalid_argument);
}

TEST(CommandLineTest, PrintParametersWritesTheEffectiveOnes) {
  const CommandLine cl = ParseCommandLine(Query(), {"--print-parameters"});
  Parameters params;
  params.dbname = "other";
  std::ostringstream out;
  EXPECT_TRUE(PrintParametersIfAsked(cl, params, out));
  EXPECT_EQ(out.str().rfind("dbname=other\n", 0), 0u) << out.str();
  EXPECT_FALSE(PrintParametersIfAsked(ParseCommandLine(Query(), {"list"}), params, out));
}

}  // namespace
}  // namespace simpartner
