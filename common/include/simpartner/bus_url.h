// LCM bus URLs as our processes open them.
#pragma once

#include <string>

namespace simpartner {

// The URL with recv_buf_size=4194304 added for udpm when it has none. A sim
// running as fast as it can sends states faster than a default socket
// buffer (about 200 kB, 70 ms of gen1 states) holds while the reader is
// busy or descheduled, and the kernel then drops whatever datagram comes
// next: a state for the logger, a command's reply for a client.
std::string WithReceiveBuffer(const std::string& url);

// A bus of one's own on this host: a udpm URL with ttl=0 (nothing leaves
// the host) and the receive buffer above, on a port that no socket holds
// now, chosen from `key` (a pid) and `offset` (0 to 99: several buses of
// one process, each its own). Ports 20000 to 59999; a taken one is passed
// over for the next candidate. Tests take one bus per test, a batch one per
// run. Throws std::runtime_error when no free port is found, or for an
// offset out of range (std::invalid_argument).
std::string PrivateBusUrl(long long key, int offset);

}  // namespace simpartner
