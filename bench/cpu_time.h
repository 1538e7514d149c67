// CPU time of this process and of a private MariaDB server, for the
// logger's benchmarks (what a figure cost besides how long it took).
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include "simpartner/logger/private_server.h"

namespace simpartner::bench {

// CPU time of this process so far [s], all threads.
inline double CpuSeconds() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
}

// CPU time the private server has used so far [s] (utime + stime from /proc).
inline double ServerCpuSeconds(const logger::PrivateServer& server) {
  std::ifstream pid_file(server.dir() + "/mariadbd.pid");
  std::string pid;
  pid_file >> pid;
  std::ifstream stat("/proc/" + pid + "/stat");
  std::string text;
  std::getline(stat, text);
  std::stringstream fields(text.substr(text.rfind(')') + 2));
  std::string f;
  double ticks = 0;
  for (int i = 3; i <= 15 && fields >> f; ++i)
    if (i == 14 || i == 15) ticks += std::stod(f);
  return ticks / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

}  // namespace simpartner::bench
