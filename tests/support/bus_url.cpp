#include "bus_url.h"

#include <unistd.h>

#include "simpartner/bus_url.h"

namespace simpartner::test_support {

std::string BusUrl(int offset) { return PrivateBusUrl(::getpid(), offset); }

}  // namespace simpartner::test_support
