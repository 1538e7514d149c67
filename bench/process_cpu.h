// CPU time of another process, for the benches that run programs beside
// each other (viewer_bench, camera_bench): what each one cost.
#pragma once

#include <sys/types.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace simpartner::bench {

// utime + stime of process `pid` so far [s], from /proc/PID/stat; -1 if it is gone.
inline double ProcessCpuSeconds(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat;
  std::getline(in, stat);
  const size_t close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream fields(stat.substr(close + 2));
  std::string field;
  double utime = 0, stime = 0;
  // Fields after "(comm)": state is field 3; utime 14, stime 15.
  for (int k = 3; k <= 15 && fields >> field; ++k) {
    if (k == 14) utime = std::atof(field.c_str());
    if (k == 15) stime = std::atof(field.c_str());
  }
  return (utime + stime) / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

}  // namespace simpartner::bench
