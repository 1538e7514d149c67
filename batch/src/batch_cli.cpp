#include "simpartner/batch/batch_cli.h"

#include <cstdlib>
#include <filesystem>
#include <thread>

#include "simpartner/batch/batch_file.h"
#include "simpartner/batch/plan.h"
#include "simpartner/batch/runner.h"
#include "simpartner/batch/slurm.h"
#include "simpartner/bus_signing.h"

namespace simpartner::batch {
namespace {

namespace fs = std::filesystem;

std::string DefaultResults(const BatchFile& batch) {
  return (fs::path("batch-results") / batch.name).string();
}

void PrintPlan(const BatchFile& batch, const std::vector<PlannedRun>& runs, std::ostream& out) {
  out << "batch '" << batch.name << "': " << runs.size() << " run(s) of "
      << batch.duration << " s in " << batch.world << "\n";
  for (const PlannedRun& run : runs) out << "  run " << run.index << ": " << RunTag(batch, run) << "\n";
}

BatchOptions MakeOptions(const CommandLine& args, const BatchFile& batch) {
  BatchOptions options;
  options.run.results_dir = args.Text("results", DefaultResults(batch));
  options.run.timeout = args.Number("timeout", 600);
  options.run.log = !args.Has("no-log");
  // simpartner-logger takes its option file as an option, the database and
  // the server as parameters (--key=value).
  std::vector<std::string>& logger_args = options.run.logger_args;
  if (args.Has("db-options"))
    logger_args.insert(logger_args.end(), {"--db-options", args.Text("db-options")});
  for (const char* key : {"dbname", "dbserver"})
    if (args.Has(key)) logger_args.push_back(std::string("--") + key + "=" + args.Text(key));
  const unsigned cores = std::thread::hardware_concurrency();
  options.parallel = static_cast<int>(args.Integer("parallel", cores > 0 ? cores : 1));
  for (const std::string& index : args.All("only")) options.only.push_back(std::stoi(index));
  options.progress = !args.Has("quiet");
  return options;
}

}  // namespace

CommandLineSpec BatchCommandLine() {
  CommandLineSpec spec;
  spec.program = "simpartner-batch";
  spec.summary =
      "Runs a batch of simulations (a sweep over parameters and controller values, seeds) "
      "described by BATCH.xml (batch/dtd/batch.dtd, docs/batch.md): every run its own sim, "
      "paused at start and as fast as possible, with its controller in lock-step, on a bus of "
      "its own, logged into one database with its values in Simulation.tag. Runs N at a time "
      "here, or (--slurm) as a Slurm job array. Runs done before are skipped, so an "
      "interrupted batch resumes. Writes RESULTS/summary.csv.";
  spec.positionals = {Positional{"BATCH.xml", 1, 1}};
  spec.options = {
      Text("results", "DIR", "where results and logs go (default batch-results/<name>)"),
      Integer("parallel", "N", "runs at a time (default: the number of cores)").Range(1, 1024),
      Number("timeout", "S", "wall seconds a run may take (default 600)").Above(0),
      Switch("no-log", "log no run into the database"),
      Text("db-options", "FILE", "the loggers' MariaDB client option file (simpartner-logger)"),
      Text("dbname", "NAME", "the loggers' database (default simpartner)"),
      Text("dbserver", "SERVER", "the loggers' server, host[:port] or a socket"),
      Switch("check", "check the batch file and print its runs; run nothing"),
      Integer("only", "I", "run only run I (repeatable; what a Slurm array task does)")
          .Range(0, 100000000),
      Switch("quiet", "no progress line"),
      Switch("slurm",
             "submit the runs as a Slurm job array (sbatch) and wait for it; the results folder "
             "and the database must be reachable from every node (docs/batch.md)"),
      Text("partition", "P", "--slurm: the partition (default: the cluster's)"),
      Text("sbatch-arg", "ARG", "--slurm: one more argument for sbatch (repeatable), e.g. "
                                "--account=lab"),
  };
  spec.epilogue =
      "Exit status: 0 every run ok; 1 a run failed or is missing (its log folder is in the "
      "summary); 2 the batch file or the command line is wrong (nothing started).";
  return spec;
}

int RunBatchProgram(const CommandLine& args, std::ostream& out, std::ostream& err) {
  const BatchParseResult parsed = LoadBatchFile(args.positional().front());
  if (!parsed.batch) {
    err << parsed.diagnostics.Format() << "\nsimpartner-batch: nothing started\n";
    return 2;
  }
  const BatchFile& batch = *parsed.batch;
  const std::vector<PlannedRun> runs = PlanRuns(batch);
  if (args.Has("check")) {
    PrintPlan(batch, runs, out);
    return 0;
  }
  const BatchOptions options = MakeOptions(args, batch);
  fs::create_directories(options.run.results_dir);
  // One key for every run (its sim, controller, logger and observer, on
  // this host or a Slurm node), chosen and said here once.
  const std::string key = ChooseBusKeyFile(
      [&err](const std::string& line) { err << "simpartner-batch: " << line << "\n"; });
  ::setenv(kBusKeyVariable, key.empty() ? kNoBusKey : key.c_str(), 1);
  BatchOutcome outcome;
  if (args.Has("slurm")) {
    SlurmOptions slurm;
    slurm.partition = args.Text("partition");
    slurm.sbatch_args = args.All("sbatch-arg");
    try {
      outcome = RunOnSlurm(batch, runs, options, slurm, err);
    } catch (const SlurmError& e) {
      err << "simpartner-batch: slurm: " << e.what() << "\n";
      return 1;
    }
  } else {
    outcome = RunBatch(batch, runs, options, err);
  }
  const std::string summary = SummaryPath(options.run.results_dir);
  WriteSummary(batch, runs, outcome.results, summary);
  out << "simpartner-batch: " << outcome.done << " run(s) done, " << outcome.failed << " failed, "
      << outcome.skipped << " done before; " << outcome.results.size() << " of " << runs.size()
      << " have results; summary " << summary << "\n";
  const bool all = options.only.empty();
  return outcome.failed == 0 && (!all || outcome.results.size() == runs.size()) ? 0 : 1;
}

}  // namespace simpartner::batch
