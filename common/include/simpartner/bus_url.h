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

}  // namespace simpartner
