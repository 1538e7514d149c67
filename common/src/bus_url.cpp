#include "simpartner/bus_url.h"

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace simpartner {
namespace {

constexpr int kFirstPort = 20000;
constexpr int kPorts = 40000;        // 20000 to 59999
constexpr int kOffsets = 100;        // buses per key (process)
constexpr int kScatter = 7919;       // a prime: neighbours land far apart
constexpr int kCandidates = 64;
constexpr int kPidStep = 37;         // the next candidate: as if the pid were 37 more

// False when some socket is bound to the port already: our processes bind
// with SO_REUSEADDR, so a bind without it fails beside any of them.
bool PortIsFree(int port) {
  const int probe = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (probe < 0) throw std::runtime_error(std::string("PrivateBusUrl: socket: ") + std::strerror(errno));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  address.sin_port = htons(static_cast<uint16_t>(port));
  const bool bound = ::bind(probe, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  ::close(probe);
  return bound;
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
