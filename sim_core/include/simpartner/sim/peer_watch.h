// Noticing another simulation on the bus. Two sims on one bus (the same
// multicast address and port) both apply every command, and a viewer or
// logger sees two models in turn; nothing else on the bus would say so.
// Every SIM_STATUS (at least once a second) and SIM_MODEL (at start and on
// request) carries its simulation id, so a sim that hears one it did not
// publish knows within a second of the other's start.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "simpartner/bus_decode.h"
#include "simpartner/bus_signing.h"

namespace simpartner::sim {

// The simulation id of a SIM_STATE, SIM_STATUS or SIM_MODEL datagram read
// without decoding it (no allocation, whatever the datagram holds): all
// three begin with utime and simulation_id, so the id is the big-endian
// int64 after the 8-byte fingerprint and utime. nullopt for another
// channel, a datagram too short, or a fingerprint not of the channel's type.
std::optional<int64_t> PeekSimulationId(const std::string& channel, const void* data,
                                        size_t size);

struct OtherSimulation {
  int64_t simulation_id = 0;
  std::string channel;  // where it was first heard
};

class PeerWatch {
 public:
  static constexpr size_t kMaxRememberedIds = 4096;

  // A message refused for its signature: its description, and whether to
  // print it now (OpenFromBus: at most a line a second).
  using RefusalReport = std::function<void(const std::string& line, bool print)>;

  // Subscribes to SIM_STATUS and SIM_MODEL on `lcm` (which must
  // outlive this) until destroyed.
  // `signing` (may be null) outlives the watch: with it, only signed
  // messages count (a forged status names no other simulation); the others
  // are counted in `refused` and passed to `report` (both may be null; the
  // counter outlives the watch).
  explicit PeerWatch(lcm::LCM* lcm, BusSigning* signing = nullptr,
                     BadMessageCounter* refused = nullptr, RefusalReport report = {});
  ~PeerWatch();
  PeerWatch(const PeerWatch&) = delete;
  PeerWatch& operator=(const PeerWatch&) = delete;

  // Ids this process published under (each start and reset has one): its
  // own messages come back over loopback and are not another simulation.
  void AddOwnId(int64_t simulation_id);
  // Simulations heard since the last call, each id once (of the last
  // kMaxRememberedIds), at most kMaxRememberedIds.
  std::vector<OtherSimulation> TakeNew();

 private:
  void OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  lcm::LCM* lcm_;
  BusSigning* signing_;
  BadMessageCounter* refused_;
  RefusalReport report_;
  std::vector<lcm::Subscription*> subscriptions_;
  std::set<int64_t> own_ids_;
  std::set<int64_t> heard_ids_;
  std::vector<OtherSimulation> new_;
};

// Before a sim starts: asks for SIM_MODEL and listens for `wait`. A sim on
// the bus answers a model request at its next input check (well under a
// millisecond at real time); a sim that never answers is caught later by
// the running sim's PeerWatch when it publishes.
std::optional<OtherSimulation> ProbeForOtherSimulation(lcm::LCM* lcm,
                                                       std::chrono::milliseconds wait,
                                                       BusSigning* signing = nullptr);

// What a user reads when another simulation is heard: the id, the channel,
// what goes wrong, and the way out.
std::string DescribeOtherSimulation(const OtherSimulation& other, const std::string& url);

}  // namespace simpartner::sim
