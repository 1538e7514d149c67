// A bus of the test's own: an LCM udpm URL with ttl=0 (nothing leaves the
// host) on a port that no other process holds, so tests run by ctest -j,
// and other checkouts' suites on the same machine, never hear each other.
#pragma once

#include <string>

namespace simpartner::test_support {

// Bus number `offset` of this test process (0 to 99; a test that needs
// several buses gives each its own number). The port comes from the pid
// and the offset; one already bound by another process (a sim, a logger,
// another test's listener) is passed over for the next candidate. Call it
// once per bus and keep the URL: once the test's own processes hold the
// port, a second call gives another. The URL asks for the receive buffer
// our processes ask for (simpartner/bus_url.h). Throws std::runtime_error
// when no free port is found.
std::string BusUrl(int offset);

}  // namespace simpartner::test_support
