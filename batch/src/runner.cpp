#include "simpartner/batch/runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>

#include "simpartner/csv_field.h"
#include "simpartner/text.h"

namespace simpartner::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A result that stands for this very run: done, with the same values.
bool AlreadyDone(const std::optional<RunResult>& result, const BatchFile& batch,
                 const PlannedRun& run) {
  return result && result->ok && result->tag == RunTag(batch, run);
}

// "[=====>    ] 12/40 runs, 1 failed, about 2 min left"
std::string ProgressLine(int finished, int total, int failed, double seconds_per_run,
                         int parallel) {
  constexpr int kWidth = 30;
  const int filled = total > 0 ? finished * kWidth / total : kWidth;
  std::string bar(static_cast<size_t>(filled), '=');
  if (filled < kWidth) bar += '>' + std::string(static_cast<size_t>(kWidth - filled - 1), ' ');
  std::string line = "[" + bar + "] " + std::to_string(finished) + "/" + std::to_string(total) +
                     " runs, " + std::to_string(failed) + " failed";
  if (finished > 0 && finished < total) {
    const double left = seconds_per_run * (total - finished) / std::max(1, parallel);
    line += left < 120 ? ", about " + FormatFixed(left, 0) + " s left"
                       : ", about " + FormatFixed(left / 60, 0) + " min left";
  }
  return line;
}

}  // namespace

BatchOutcome RunBatch(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                      const BatchOptions& options, std::ostream& progress_out) {
  BatchOutcome outcome;
  std::vector<const PlannedRun*> todo;
  for (const PlannedRun& run : runs) {
    if (!options.only.empty() &&
        std::find(options.only.begin(), options.only.end(), run.index) == options.only.end())
      continue;
    if (AlreadyDone(ReadResult(ResultPath(options.run.results_dir, run.index)), batch, run))
      ++outcome.skipped;
    else
      todo.push_back(&run);
  }
  std::mutex mutex;
  std::atomic<size_t> next{0};
  const Clock::time_point start = Clock::now();
  auto report = [&] {
    if (!options.progress) return;
    const int finished = outcome.done + outcome.failed;
    const double per_run =
        finished > 0 ? std::chrono::duration<double>(Clock::now() - start).count() *
                           std::max(1, options.parallel) / finished
                     : 0;
    progress_out << "\r" << ProgressLine(finished, static_cast<int>(todo.size()), outcome.failed,
                                         per_run, options.parallel)
                 << std::flush;
  };
  report();
  auto worker = [&] {
    for (size_t i; (i = next++) < todo.size();) {
      const RunResult result = RunOne(batch, *todo[i], options.run);
      WriteResult(result, ResultPath(options.run.results_dir, result.index));
      std::lock_guard<std::mutex> lock(mutex);
      (result.ok ? outcome.done : outcome.failed) += 1;
      if (!result.ok && options.progress)
        progress_out << "\rrun " << result.index << " (" << result.tag << ") failed: " << result.status
                     << "; logs in " << result.log_dir << "\n";
      report();
    }
  };
  std::vector<std::thread> workers;
  for (int k = 0; k < std::max(1, options.parallel); ++k) workers.emplace_back(worker);
  for (std::thread& t : workers) t.join();
  if (options.progress) progress_out << "\n";
  outcome.results = CollectResults(runs, batch, options.run.results_dir);
  return outcome;
}

std::vector<RunResult> CollectResults(const std::vector<PlannedRun>& runs,
                                      const BatchFile& batch, const std::string& results_dir) {
  std::vector<RunResult> results;
  for (const PlannedRun& run : runs) {
    std::optional<RunResult> r = ReadResult(ResultPath(results_dir, run.index));
    if (r && r->tag == RunTag(batch, run)) results.push_back(std::move(*r));
  }
  return results;
}

std::string SummaryPath(const std::string& results_dir) {
  return (fs::path(results_dir) / "summary.csv").string();
}

void WriteSummary(const BatchFile& batch, const std::vector<PlannedRun>& runs,
                  const std::vector<RunResult>& results, const std::string& path) {
  std::ofstream out(path);
  out << "run,seed";
  for (const Vary& v : batch.sweep) out << "," << v.name;
  out << ",status,last_step,sim_time,wall_seconds,state_hash";
  for (const Figure& f : batch.figures) out << "," << f.name;
  out << ",log_dir\n";
  for (const PlannedRun& run : runs) {
    const auto r = std::find_if(results.begin(), results.end(),
                                [&](const RunResult& x) { return x.index == run.index; });
    out << run.index << "," << run.seed;
    for (const auto& [name, value] : run.values) out << "," << CsvField(value);
    if (r == results.end()) {
      out << ",missing,,,,";
      for (size_t i = 0; i < batch.figures.size(); ++i) out << ",";
      out << ",\n";
      continue;
    }
    out << "," << CsvField(r->status) << "," << r->last_step << "," << ShortestNumber(r->sim_time)
        << "," << FormatFixed(r->wall_seconds, 3) << "," << r->state_hash;
    for (const double value : r->figures) out << "," << ShortestNumber(value);
    out << "," << CsvField(r->log_dir) << "\n";
  }
}

}  // namespace simpartner::batch
