#include "netns.h"

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "simpartner/child_process.h"

namespace simpartner::test_support {
namespace {

constexpr const char* kIp = "/usr/sbin/ip";
constexpr const char* kBridge = "br0";

std::string Joined(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) line += (line.empty() ? "" : " ") + a;
  return line;
}

}  // namespace

std::string RunCommand(const std::vector<std::string>& argv) {
  char path[] = "/tmp/sp_netns_cmd_XXXXXX";
  const int fd = ::mkstemp(path);
  if (fd < 0) throw NetnsError(std::string("cannot make a temporary file: ") + std::strerror(errno));
  ::close(fd);
  std::optional<int> status;
  {
    ChildProcess child(argv, path);
    status = child.Wait(std::chrono::seconds(30));
  }
  std::ifstream in(path);
  std::stringstream out;
  out << in.rdbuf();
  std::filesystem::remove(path);
  if (status.value_or(-1) != 0)
    throw NetnsError("'" + Joined(argv) + "' " +
                     (status ? "exited with " + std::to_string(*status) : std::string("did not end in 30 s")) +
                     ": " + out.str());
  return out.str();
}

NamespaceLan::NamespaceLan(const std::string& prefix, const std::vector<std::string>& hosts)
    : hosts_(hosts) {
  const int pid = static_cast<int>(::getpid());
  subnet_ = "10.214." + std::to_string(pid % 250) + ".";
  const std::string switch_ns = prefix + "_" + std::to_string(pid) + "_sw";
  try {
    auto add_namespace = [&](const std::string& name) {
      RunCommand({kIp, "netns", "add", name});
      namespaces_.push_back(name);
      RunCommand({kIp, "-n", name, "link", "set", "lo", "up"});
    };
    for (const std::string& host : hosts_) add_namespace(prefix + "_" + std::to_string(pid) + "_" + host);
    add_namespace(switch_ns);
    // No IGMP snooping: every port gets every group, as on a plain switch,
    // with no querier needed to keep memberships alive.
    RunCommand({kIp, "-n", switch_ns, "link", "add", kBridge, "type", "bridge", "mcast_snooping", "0"});
    RunCommand({kIp, "-n", switch_ns, "link", "set", kBridge, "up"});
    for (size_t i = 0; i < hosts_.size(); ++i) {
      const std::string port = "p" + std::to_string(i);
      const std::string ns = namespaces_[i];
      const std::string dev = Interface(hosts_[i]);
      // Made inside the switch namespace, its peer straight in the host's.
      RunCommand({kIp, "-n", switch_ns, "link", "add", port, "type", "veth", "peer", "name", dev, "netns", ns});
      RunCommand({kIp, "-n", switch_ns, "link", "set", port, "master", kBridge});
      RunCommand({kIp, "-n", switch_ns, "link", "set", port, "up"});
      RunCommand({kIp, "-n", ns, "addr", "add", Address(hosts_[i]) + "/24", "dev", dev});
      RunCommand({kIp, "-n", ns, "link", "set", dev, "up"});
      RunCommand({kIp, "-n", ns, "route", "add", "224.0.0.0/4", "dev", dev});
    }
  } catch (...) {
    Remove();
    throw;
  }
}

NamespaceLan::~NamespaceLan() { Remove(); }

void NamespaceLan::Remove() noexcept {
  for (auto it = namespaces_.rbegin(); it != namespaces_.rend(); ++it) {
    try {
      RunCommand({kIp, "netns", "del", *it});
    } catch (const std::exception&) {
      // Nothing more to do in a destructor; a leftover is named by its pid.
    }
  }
  namespaces_.clear();
}

size_t NamespaceLan::Index(const std::string& host) const {
  for (size_t i = 0; i < hosts_.size(); ++i)
    if (hosts_[i] == host) return i;
  throw NetnsError("no host '" + host + "' in this network (hosts: " + Joined(hosts_) + ")");
}

const std::string& NamespaceLan::Namespace(const std::string& host) const { return namespaces_.at(Index(host)); }

std::string NamespaceLan::Interface(const std::string& host) const { return "eth" + std::to_string(Index(host)); }

std::string NamespaceLan::Address(const std::string& host) const {
  return subnet_ + std::to_string(Index(host) + 1);
}

std::vector<std::string> NamespaceLan::Exec(const std::string& host,
                                            const std::vector<std::string>& argv) const {
  std::vector<std::string> out = {kIp, "netns", "exec", Namespace(host)};
  out.insert(out.end(), argv.begin(), argv.end());
  return out;
}

void NamespaceLan::SetLink(const std::string& host, bool up) const {
  RunCommand({kIp, "-n", Namespace(host), "link", "set", "dev", Interface(host), up ? "up" : "down"});
  // The kernel drops a device's static routes when it goes down; a host's
  // network configuration puts them back when it comes up (ifupdown's
  // "up" lines, NetworkManager), and so does this.
  if (up) RunCommand({kIp, "-n", Namespace(host), "route", "replace", "224.0.0.0/4", "dev", Interface(host)});
}

ScopedNetns::ScopedNetns(const std::string& name) {
  original_ = ::open("/proc/thread-self/ns/net", O_RDONLY | O_CLOEXEC);
  if (original_ < 0) throw NetnsError(std::string("cannot open this thread's network namespace: ") + std::strerror(errno));
  const std::string path = "/run/netns/" + name;
  const int target = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (target < 0) {
    const std::string cause = std::strerror(errno);
    ::close(original_);
    throw NetnsError("cannot open network namespace " + path + ": " + cause);
  }
  const int entered = ::setns(target, CLONE_NEWNET);
  const std::string cause = std::strerror(errno);
  ::close(target);
  if (entered != 0) {
    ::close(original_);
    throw NetnsError("cannot enter network namespace " + path + ": " + cause);
  }
}

ScopedNetns::~ScopedNetns() {
  // Back where the thread was; failing that the thread would stay inside.
  if (::setns(original_, CLONE_NEWNET) != 0) std::abort();
  ::close(original_);
}

}  // namespace simpartner::test_support
