// A single-node Slurm of the test's own (Debian's slurm-wlm and munge, run
// as root without systemd): munged with its own key and socket, slurmctld
// and slurmd on loopback with private ports and directories, and a
// partition of this host. Clients (sbatch, squeue) find it through
// SLURM_CONF, which the object sets for this process (and so its children)
// while it lives. Everything is stopped, by PID, and removed when it goes.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "simpartner/child_process.h"

namespace simpartner::test_support {

class PrivateSlurm {
 public:
  // Starts it in `dir` (created) and waits until the node is idle (30 s);
  // throws std::runtime_error with the daemons' logs when it is not.
  explicit PrivateSlurm(const std::filesystem::path& dir);
  ~PrivateSlurm();
  PrivateSlurm(const PrivateSlurm&) = delete;
  PrivateSlurm& operator=(const PrivateSlurm&) = delete;

  std::string conf() const { return (dir_ / "slurm.conf").string(); }

 private:
  void WriteConf(const std::string& host) const;
  std::string Logs() const;

  std::filesystem::path dir_;
  std::unique_ptr<ChildProcess> munged_, slurmctld_, slurmd_;
};

}  // namespace simpartner::test_support
