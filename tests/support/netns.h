// Network namespaces standing for several hosts on one machine, shared by
// the multi-host process test and bench/multi_host_bench: a "switch"
// namespace holding a bridge, one namespace per host joined to it by a
// veth pair, addresses on a private /24 and a multicast route, so LCM
// with ttl=1 crosses from host to host and nothing reaches the real
// network (the root namespace's interfaces are never touched). Needs root.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner::test_support {

// An `ip` command that failed, or a namespace that could not be entered:
// the command line and what it printed.
class NetnsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class NamespaceLan {
 public:
  // Namespaces "<prefix>_<pid>_<host>" for each host and "<prefix>_<pid>_sw"
  // for the bridge; host i gets 10.214.<pid % 250>.<i + 1>/24. Throws
  // NetnsError (saying which command failed and why) and removes what it
  // made if any step fails.
  NamespaceLan(const std::string& prefix, const std::vector<std::string>& hosts);
  NamespaceLan(const NamespaceLan&) = delete;
  NamespaceLan& operator=(const NamespaceLan&) = delete;
  // Deletes every namespace it created; their veths and the bridge go with
  // them (processes still inside keep theirs alive until they end).
  ~NamespaceLan();

  const std::string& Namespace(const std::string& host) const;
  // The host's end of its veth pair, inside its namespace.
  std::string Interface(const std::string& host) const;
  std::string Address(const std::string& host) const;
  // argv run inside the host's namespace (`ip netns exec` becomes argv[0],
  // so a ChildProcess's pid is the program's own).
  std::vector<std::string> Exec(const std::string& host, const std::vector<std::string>& argv) const;
  // The host's link up or down (a cable pulled); up also restores the
  // multicast route, which the kernel removed with the link.
  void SetLink(const std::string& host, bool up) const;

 private:
  size_t Index(const std::string& host) const;
  void Remove() noexcept;

  std::vector<std::string> hosts_;
  std::vector<std::string> namespaces_;  // hosts_[i] -> namespaces_[i]; the switch last
  std::string subnet_;
};

// The calling thread inside a named namespace (/run/netns/NAME) for the
// object's lifetime: sockets made meanwhile (an lcm::LCM and its
// subscriptions) stay in that namespace afterwards.
class ScopedNetns {
 public:
  explicit ScopedNetns(const std::string& name);
  ScopedNetns(const ScopedNetns&) = delete;
  ScopedNetns& operator=(const ScopedNetns&) = delete;
  ~ScopedNetns();

 private:
  int original_ = -1;
};

// Runs argv (no shell), returns its output; throws NetnsError with the
// command line and the output when it exits non-zero.
std::string RunCommand(const std::vector<std::string>& argv);

}  // namespace simpartner::test_support
