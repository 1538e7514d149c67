// How much this process has not yet read from its UDP sockets: what the
// kernel holds for it (/proc/net/udp's rx_queue of each of its sockets).
// A reader that must know whether everything already sent has been read
// (a logger told to stop) cannot tell from time alone: stopped or starved
// of CPU, it hears nothing for a while with datagrams waiting.
#pragma once

#include <cstddef>
#include <optional>

namespace simpartner {

// Bytes waiting in the UDP sockets (IPv4 and IPv6) this process holds
// open, in the process's network namespace; nullopt when /proc cannot be
// read.
std::optional<size_t> UnreadUdpBytes();

}  // namespace simpartner
