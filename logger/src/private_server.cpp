#include "simpartner/logger/private_server.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "simpartner/child_process.h"

namespace simpartner::logger {

PrivateServer::PrivateServer(std::string script, std::string dir, bool remove_dir, std::string seed)
    : script_(std::move(script)), dir_(std::move(dir)), remove_dir_(remove_dir), seed_(std::move(seed)) {
  std::filesystem::create_directories(dir_);
}

PrivateServer::~PrivateServer() {
  try {
    if (started_) Stop();
  } catch (const std::exception&) {
    // Stopping is best effort here; the script kills a server that hangs.
  }
  if (remove_dir_) {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
}

void PrivateServer::RunScript(const std::string& command) {
  const std::string log = dir_ + "/script-" + command + ".log";
  std::vector<std::string> argv = {"/bin/bash", script_, command, "--datadir", dir_};
  if (command == "start" && !seed_.empty()) argv.insert(argv.end(), {"--seed", seed_});
  ChildProcess child(argv, log);
  const std::optional<int> status = child.Wait(std::chrono::seconds(120));
  if (status == 0) return;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  throw Error("scripts/mariadb " + command + " --datadir " + dir_ + " failed (" +
              (status ? "exit " + std::to_string(*status) : std::string("timeout")) + "): " +
              text.str());
}

void PrivateServer::Start() {
  RunScript("start");
  started_ = true;
}

void PrivateServer::Stop() {
  RunScript("stop");
  started_ = false;
}

DbTarget PrivateServer::LoggerTarget(const std::string& database) const {
  DbTarget t;
  t.option_file = logger_options();
  t.socket = socket();
  t.database = database;
  return t;
}

DbTarget PrivateServer::AdminTarget(const std::string& database) const {
  DbTarget t;
  t.option_file = admin_options();
  t.socket = socket();
  t.database = database;
  return t;
}

}  // namespace simpartner::logger
