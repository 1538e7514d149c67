// Timing in interleaved rounds: benchmarks that compare variants step
// each in turn, a round at a time, and print the median round, so that
// a machine whose speed drifts (other load, a busy neighbour) shifts
// every variant alike and single stalls do not move the figures.
#pragma once

#include <time.h>

#include <algorithm>
#include <vector>

namespace simpartner::bench {

// CPU time of the calling thread [s]: other processes count less.
inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

// The value at fraction q (0..1) of `values` sorted (nearest rank).
inline double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto at = static_cast<size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
  return values[std::min(at, values.size() - 1)];
}

inline double Median(const std::vector<double>& values) { return Quantile(values, 0.5); }

}  // namespace simpartner::bench
