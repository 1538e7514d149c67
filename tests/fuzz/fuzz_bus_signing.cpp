// libFuzzer target: BusSigning::Open (common/bus_signing.h) on arbitrary
// datagrams. Whatever the bytes, it returns a size within the datagram
// and, without the key, never takes one as signed: a forger's best guess
// at the 128-bit tag is refused.
#include <cstddef>
#include <cstdint>

#include "simpartner/bus_signing.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static simpartner::BusSigning reader(simpartner::BusSigning::Key{});
  const simpartner::BusSigning::Opened opened = reader.Open("SIM_COMMAND", data, size, 0);
  if (opened.size > size || opened.refusal.empty()) __builtin_trap();
  if (simpartner::UnsignedSize(data, size) > size) __builtin_trap();
  return 0;
}
