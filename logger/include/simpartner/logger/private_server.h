// A private MariaDB server in a directory of its own, started and stopped
// through scripts/mariadb (the same script the run command uses): for tests
// and benchmarks, which must not share a server or a port.
#pragma once

#include <string>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

class PrivateServer {
 public:
  // script: path of scripts/mariadb. dir: created if missing; with
  // remove_dir the destructor deletes it after stopping the server. seed:
  // when not empty, a new data directory is a copy of the one a server
  // left there (scripts/mariadb start --seed), not made from nothing.
  PrivateServer(std::string script, std::string dir, bool remove_dir, std::string seed = {});
  PrivateServer(const PrivateServer&) = delete;
  PrivateServer& operator=(const PrivateServer&) = delete;
  ~PrivateServer();

  // Throw Error with the script's output when it fails.
  void Start();
  void Stop();

  const std::string& dir() const { return dir_; }
  std::string socket() const { return dir_ + "/mysqld.sock"; }
  std::string logger_options() const { return dir_ + "/logger.cnf"; }
  std::string reader_options() const { return dir_ + "/reader.cnf"; }
  std::string admin_options() const { return dir_ + "/admin.cnf"; }
  // Where the logger writes, in database `database`.
  DbTarget LoggerTarget(const std::string& database) const;
  // The administrator (root over the socket), for tests that change the
  // server (read-only) or look behind the logger's back.
  DbTarget AdminTarget(const std::string& database) const;

 private:
  void RunScript(const std::string& command);
  std::string script_;
  std::string dir_;
  bool remove_dir_;
  std::string seed_;
  bool started_ = false;
};

}  // namespace simpartner::logger
