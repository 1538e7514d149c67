#include "simpartner/bus_url.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace simpartner {
namespace {

constexpr int kFirstPort = 20000;
constexpr int kPorts = 40000;        // 20000 to 59999
constexpr int kOffsets = 100;        // buses per key (process)
constexpr int kScatter = 7919;       // a prime: neighbours land far apart
constexpr int kCandidates = 64;
constexpr int kPidStep = 37;         // the next candidate: as if the pid were 37 more

// False when some UDP socket on this host is bound to the port already
// (/proc/net/udp and udp6 list them all, whatever their options). Read, not
// probed with a bind: a probing bind without SO_REUSEADDR, however brief,
// made another process's LCM bind on that port fail ("bind: Address
// already in use") and its bus deaf.
bool PortIsFree(int port) {
  char wanted[8];
  std::snprintf(wanted, sizeof wanted, ":%04X", static_cast<unsigned>(port));
  for (const char* table : {"/proc/net/udp", "/proc/net/udp6"}) {
    std::ifstream in(table);
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) {
      // "  sl  local_address rem_address ...": the local address is the
      // second field, "ADDRESS:PORT" in hex.
      std::istringstream fields(line);
      std::string slot, local;
      fields >> slot >> local;
      const size_t colon = local.rfind(':');
      if (colon != std::string::npos && local.compare(colon, std::string::npos, wanted) == 0)
        return false;
    }
  }
  return true;
}

}  // namespace

std::string WithReceiveBuffer(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos) return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=4194304";
}

std::string PrivateBusUrl(long long key, int offset) {
  if (offset < 0 || offset >= kOffsets)
    throw std::invalid_argument("PrivateBusUrl: offset " + std::to_string(offset) + " is not in 0 to " +
                                std::to_string(kOffsets - 1));
  // Every candidate is offset modulo kOffsets (kPorts is a multiple of
  // it), so two offsets of one process never share a port.
  const long long first = (key % kPorts + kPorts) % kPorts * kOffsets + offset;
  for (int k = 0; k < kCandidates; ++k) {
    const long long index = (first + static_cast<long long>(k) * kPidStep * kOffsets) % kPorts;
    const int port = kFirstPort + static_cast<int>(index * kScatter % kPorts);
    if (PortIsFree(port))
      return WithReceiveBuffer("udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0");
  }
  throw std::runtime_error("PrivateBusUrl: no free udp port among " + std::to_string(kCandidates) +
                           " candidates for offset " + std::to_string(offset));
}

}  // namespace simpartner
