#include "slurm.h"

#include <signal.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "processes.h"
#include "text_file.h"

namespace simpartner::test_support {
namespace {

namespace fs = std::filesystem;

std::string ShortHostName() {
  char name[256] = {0};
  ::gethostname(name, sizeof name - 1);
  const std::string host = name;
  return host.substr(0, host.find('.'));
}

// Two ports of this process's own for slurmctld and slurmd.
int PortBase() { return 30000 + static_cast<int>(::getpid() % 10000) * 2; }

}  // namespace

PrivateSlurm::PrivateSlurm(const fs::path& dir) : dir_(dir) {
  fs::create_directories(dir_ / "ctld");
  fs::create_directories(dir_ / "d");
  ::chmod(dir_.c_str(), 0700);  // munged refuses a key or socket others could reach
  const std::string host = ShortHostName();
  const ProgramRun key = RunToEnd({"/usr/sbin/mungekey", "-c", "-f", "-k", (dir_ / "munge.key").string()},
                                  (dir_ / "mungekey.log").string(), std::chrono::seconds(30));
  if (key.status != 0) throw std::runtime_error("mungekey failed: " + key.output);
  munged_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/sbin/munged", "-F", "-f",
                               "--key-file=" + (dir_ / "munge.key").string(),
                               "--socket=" + (dir_ / "munge.socket").string(),
                               "--pid-file=" + (dir_ / "munged.pid").string(),
                               "--log-file=" + (dir_ / "munged.log").string(),
                               "--seed-file=" + (dir_ / "munged.seed").string()},
      (dir_ / "munged.out").string());
  WriteConf(host);
  ::setenv("SLURM_CONF", conf().c_str(), 1);
  slurmctld_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/sbin/slurmctld", "-D", "-f", conf()},
      (dir_ / "slurmctld.out").string());
  slurmd_ = std::make_unique<ChildProcess>(
      std::vector<std::string>{"/usr/sbin/slurmd", "-D", "-f", conf(), "-N", host},
      (dir_ / "slurmd.out").string());
  for (int tries = 0; tries < 60; ++tries) {
    const ProgramRun sinfo = RunToEnd({"/usr/bin/sinfo", "-h", "-o", "%t"},
                                      (dir_ / "sinfo.log").string(), std::chrono::seconds(10));
    if (sinfo.status == 0 && sinfo.output.find("idle") != std::string::npos) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  throw std::runtime_error("the private Slurm's node is not idle after 30 s\n" + Logs());
}

PrivateSlurm::~PrivateSlurm() {
  for (auto* daemon : {&slurmd_, &slurmctld_, &munged_})
    if (*daemon) {
      (*daemon)->Signal(SIGTERM);
      if (!(*daemon)->Wait(std::chrono::seconds(10))) (*daemon)->Signal(SIGKILL);
    }
  ::unsetenv("SLURM_CONF");
}

void PrivateSlurm::WriteConf(const std::string& host) const {
  const std::string d = dir_.string();
  std::ofstream(conf()) << "ClusterName=sptest" << ::getpid() << "\n"
                        << "SlurmctldHost=" << host << "(127.0.0.1)\n"
                        << "SlurmctldPort=" << PortBase() << "\nSlurmdPort=" << PortBase() + 1 << "\n"
                        << "SlurmUser=root\nSlurmdUser=root\n"
                        << "AuthType=auth/munge\nCredType=cred/munge\n"
                        << "AuthInfo=socket=" << d << "/munge.socket\n"
                        << "StateSaveLocation=" << d << "/ctld\nSlurmdSpoolDir=" << d << "/d\n"
                        << "SlurmctldPidFile=" << d << "/slurmctld.pid\n"
                        << "SlurmdPidFile=" << d << "/slurmd.pid\n"
                        << "SlurmctldLogFile=" << d << "/slurmctld.log\n"
                        << "SlurmdLogFile=" << d << "/slurmd.log\n"
                        << "ProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
                        << "SchedulerType=sched/backfill\nSelectType=select/cons_tres\n"
                        << "SelectTypeParameters=CR_Core\nReturnToService=2\nMpiDefault=none\n"
                        << "JobAcctGatherType=jobacct_gather/none\n"
                        << "AccountingStorageType=accounting_storage/none\n"
                        << "NodeName=" << host << " NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN\n"
                        << "PartitionName=test Nodes=" << host
                        << " Default=YES MaxTime=INFINITE State=UP\n";
}

std::string PrivateSlurm::Logs() const {
  std::string logs;
  for (const char* log : {"munged.log", "munged.out", "slurmctld.log", "slurmctld.out",
                          "slurmd.log", "slurmd.out"})
    logs += std::string("--- ") + log + "\n" + ReadText(dir_ / log);
  return logs;
}

}  // namespace simpartner::test_support
