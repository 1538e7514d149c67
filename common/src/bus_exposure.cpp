#include "simpartner/bus_exposure.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <cstdlib>

namespace simpartner {
namespace {

// "eth0 10.0.0.5, wlan0 192.168.1.4": the interfaces up with an IPv4
// address, loopback aside.
std::string OutwardInterfaces() {
  ifaddrs* all = nullptr;
  if (::getifaddrs(&all) != 0) return "";
  std::string names;
  for (const ifaddrs* i = all; i != nullptr; i = i->ifa_next) {
    if (i->ifa_addr == nullptr || i->ifa_addr->sa_family != AF_INET) continue;
    if ((i->ifa_flags & IFF_UP) == 0 || (i->ifa_flags & IFF_LOOPBACK) != 0) continue;
    char address[INET_ADDRSTRLEN] = {0};
    ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr, address,
                sizeof address);
    names += (names.empty() ? "" : ", ") + std::string(i->ifa_name) + " " + address;
  }
  ::freeifaddrs(all);
  return names;
}

}  // namespace

std::string BusExposureWarning(const std::string& url, bool signed_bus) {
  if (signed_bus || url.rfind("udpm://", 0) != 0) return "";
  if (const char* said = std::getenv(kBusExposureSaidVariable); said != nullptr && *said != '\0')
    return "";
  const std::string interfaces = OutwardInterfaces();
  if (interfaces.empty()) return "";
  const size_t colon = url.find(':', 7);
  const std::string port =
      colon == std::string::npos ? "7667" : url.substr(colon + 1, url.find('?') - colon - 1);
  return "the bus " + url + " takes datagrams from any machine on " + interfaces +
         " (whatever its ttl): anyone there can command the robot. Close it with 'sudo "
         "scripts/bus-guard on " + port + "', or sign it (leave SIMPARTNER_BUS_KEY unset, or "
         "name a key file); docs/security.md. (" + kBusExposureSaidVariable +
         "=1 stops this line.)";
}

}  // namespace simpartner
