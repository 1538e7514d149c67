#include "simpartner/batch/plan.h"

#include <sstream>

namespace simpartner::batch {
namespace {

// The value indices of combination `k` of a grid: the last vary turns
// fastest, as nested loops in the file's order would.
std::vector<size_t> GridIndices(const std::vector<Vary>& sweep, size_t k) {
  std::vector<size_t> indices(sweep.size());
  for (size_t i = sweep.size(); i-- > 0;) {
    indices[i] = k % sweep[i].values.size();
    k /= sweep[i].values.size();
  }
  return indices;
}

size_t Combinations(const BatchFile& batch) {
  if (batch.sweep.empty()) return 1;
  if (!batch.grid) return batch.sweep.front().values.size();
  size_t n = 1;
  for (const Vary& v : batch.sweep) n *= v.values.size();
  return n;
}

std::string Replace(std::string text, const std::string& name, const std::string& value) {
  const std::string placeholder = "{" + name + "}";
  for (size_t at = text.find(placeholder); at != std::string::npos;
       at = text.find(placeholder, at + value.size()))
    text.replace(at, placeholder.size(), value);
  return text;
}

}  // namespace

std::vector<PlannedRun> PlanRuns(const BatchFile& batch) {
  std::vector<PlannedRun> runs;
  for (size_t k = 0; k < Combinations(batch); ++k) {
    const std::vector<size_t> indices =
        batch.grid ? GridIndices(batch.sweep, k) : std::vector<size_t>(batch.sweep.size(), k);
    for (const long long seed : batch.seeds) {
      PlannedRun run;
      run.index = static_cast<int>(runs.size());
      run.seed = seed;
      run.parameters = batch.parameters;
      for (size_t i = 0; i < batch.sweep.size(); ++i) {
        const Vary& v = batch.sweep[i];
        run.values.emplace_back(v.name, v.values[indices[i]]);
        if (v.is_parameter) run.parameters.emplace_back(v.name, v.values[indices[i]]);
      }
      runs.push_back(std::move(run));
    }
  }
  return runs;
}

std::vector<std::string> ControllerArgv(const BatchFile& batch, const PlannedRun& run,
                                        const std::string& url) {
  std::istringstream in(batch.controller);
  std::vector<std::string> argv;
  for (std::string word; in >> word;) {
    word = Replace(word, "url", url);
    word = Replace(word, "seed", std::to_string(run.seed));
    word = Replace(word, "run", std::to_string(run.index));
    word = Replace(word, "batch", batch.name);
    for (const auto& [name, value] : run.values) word = Replace(word, name, value);
    argv.push_back(word);
  }
  return argv;
}

std::string RunTag(const BatchFile& batch, const PlannedRun& run) {
  std::string tag = "batch=" + batch.name + " run=" + std::to_string(run.index);
  for (const auto& [name, value] : run.values) tag += " " + name + "=" + value;
  if (batch.seeds.size() > 1 || batch.seeds.front() != 0) tag += " seed=" + std::to_string(run.seed);
  return tag;
}

}  // namespace simpartner::batch
