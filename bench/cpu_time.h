// CPU time of this process and of a private MariaDB server, for the
// logger's benchmarks (what a figure cost besides how long it took).
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "process_cpu.h"
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
  pid_t pid = 0;
  pid_file >> pid;
  return ProcessCpuSeconds(pid);
}

}  // namespace simpartner::bench
