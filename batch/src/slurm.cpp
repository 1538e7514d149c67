#include "simpartner/batch/slurm.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "simpartner/child_process.h"
#include "simpartner/programs.h"
#include "simpartner/text.h"

namespace simpartner::batch {
namespace {

namespace fs = std::filesystem;

// Runs a Slurm command to its end; its output. Throws SlurmError when it
// cannot start, does not end within `timeout`, or fails.
std::string Call(const std::vector<std::string>& argv, const fs::path& log, double timeout) {
  ChildProcess child(argv, log.string());
  const auto status =
      child.Wait(std::chrono::milliseconds(static_cast<int64_t>(timeout * 1000)));
  std::stringstream output;
  output << std::ifstream(log).rdbuf();
  if (!status)
    throw SlurmError(argv[0] + " did not answer within " + FormatNumber(timeout) +
                     " s: is slurmctld running and reachable? (scontrol ping)");
  if (*status != 0)
    throw SlurmError(argv[0] + " failed (status " + std::to_string(*status) + "): " +
                     Trim(output.str()));
  return output.str();
}

std::string Quoted(const std::string& word) {
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The job script: every task is simpartner-batch itself on one run.
std::string JobScript(const BatchFile& batch, const BatchOptions& options, const fs::path& dir) {
  std::string self = SiblingProgram("simpartner-batch");
  if (self.empty()) self = fs::read_symlink("/proc/self/exe").string();
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "#SBATCH --job-name=simpartner-" << batch.name << "\n"
    << "#SBATCH --output=" << (dir / "task-%a.out").string() << "\n"
    << "#SBATCH --time=" << static_cast<long>(std::ceil(options.run.timeout * 1.5 / 60)) + 1
    << "\n"
    << "exec " << Quoted(self) << " " << Quoted(fs::absolute(batch.file).string())
    << " --results " << Quoted(fs::absolute(options.run.results_dir).string())
    << " --only \"$SLURM_ARRAY_TASK_ID\" --parallel 1 --quiet --timeout "
    << ShortestNumber(options.run.timeout) << (options.run.log ? "" : " --no-log");
  for (const std::string& arg : options.run.logger_args) s << " " << Quoted(arg);
  s << "\n";
  return s.str();
}

std::string ArrayIndices(const std::vector<int>& indices) {
  std::string list;
  for (const int i : indices) list += (list.empty() ? "" : ",") + std::to_string(i);
  return list;
}

// The runs of `runs` not done yet.
std::vector<int> Pending(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                         const std::string& results_dir) {
  std::vector<int> pending;
  for (const PlannedRun& run : runs) {
    const auto r = ReadResult(ResultPath(results_dir, run.index));
    if (!r || !r->ok || r->tag != RunTag(batch, run)) pending.push_back(run.index);
  }
  return pending;
}

// Waits until squeue lists no task of the job.
void WaitForJob(const std::string& job, const SlurmOptions& slurm, const fs::path& dir,
                const BatchFile& batch, const std::vector<PlannedRun>& runs,
                const std::string& results_dir, std::ostream& progress_out) {
  const std::string squeue = ProgramOnPath("squeue");
  if (squeue.empty()) throw SlurmError("squeue is not on PATH (Debian: slurm-client)");
  for (;;) {
    const std::string queued = Call({squeue, "-h", "-j", job, "-o", "%i"}, dir / "squeue.out",
                                    slurm.answer_timeout);
    const size_t left = runs.size() - (Pending(batch, runs, results_dir).size());
    progress_out << "\rslurm job " << job << ": " << left << "/" << runs.size()
                 << " runs have results" << std::flush;
    if (Trim(queued).empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int64_t>(slurm.poll_period * 1000)));
  }
  progress_out << "\n";
}

}  // namespace

BatchOutcome RunOnSlurm(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                        const BatchOptions& options, const SlurmOptions& slurm,
                        std::ostream& progress_out) {
  const std::string sbatch = ProgramOnPath("sbatch");
  if (sbatch.empty())
    throw SlurmError("sbatch is not on PATH: Slurm's client is not installed here (Debian: "
                     "slurm-client; on a cluster, run this on a login node)");
  const fs::path dir = fs::path(options.run.results_dir) / "slurm";
  fs::create_directories(dir);
  BatchOutcome outcome;
  const std::vector<int> pending = Pending(batch, runs, options.run.results_dir);
  outcome.skipped = static_cast<int>(runs.size() - pending.size());
  if (!pending.empty()) {
    std::ofstream(dir / "job.sh") << JobScript(batch, options, dir);
    std::vector<std::string> argv = {sbatch, "--parsable", "--array=" + ArrayIndices(pending)};
    if (!slurm.partition.empty()) argv.push_back("--partition=" + slurm.partition);
    argv.insert(argv.end(), slurm.sbatch_args.begin(), slurm.sbatch_args.end());
    argv.push_back((dir / "job.sh").string());
    const std::string answer = Trim(Call(argv, dir / "sbatch.out", slurm.answer_timeout));
    const std::string job = answer.substr(0, answer.find(';'));
    progress_out << "slurm job " << job << ": " << pending.size() << " run(s) as array tasks "
                 << ArrayIndices(pending) << "; task logs in " << dir.string() << "\n";
    WaitForJob(job, slurm, dir, batch, runs, options.run.results_dir, progress_out);
  }
  outcome.results = CollectResults(runs, batch, options.run.results_dir);
  for (const RunResult& r : outcome.results) {
    const bool now = std::find(pending.begin(), pending.end(), r.index) != pending.end();
    if (now) (r.ok ? outcome.done : outcome.failed) += 1;
  }
  return outcome;
}

}  // namespace simpartner::batch
