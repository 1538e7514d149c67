// Whether machines other than this host can put datagrams on the bus, said
// once at start by the sim, the logger and every client. LCM listens on
// 0.0.0.0:PORT whatever the URL's ttl (docs/security.md, "Who can reach the
// bus"), so any machine on a network this host is on can command the robot
// unless the bus is signed (the default) or scripts/bus-guard drops
// such datagrams. A launcher that has dealt with it (scripts/run: it turned
// the guard on, or said so itself) sets SIMPARTNER_BUS_EXPOSURE_SAID=1 for
// its children, and a user who has read the warning may set it too.
#pragma once

#include <string>

namespace simpartner {

inline constexpr const char* kBusExposureSaidVariable = "SIMPARTNER_BUS_EXPOSURE_SAID";

// "" when the bus is signed, `url` is not udpm, the variable above is set,
// or this host has no network interface up but loopback; else the warning,
// naming the interfaces and the ways to close the bus.
std::string BusExposureWarning(const std::string& url, bool signed_bus);

}  // namespace simpartner
