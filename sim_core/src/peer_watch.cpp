#include "simpartner/sim/peer_watch.h"

#include "simpartner/channels.h"
#include "simpartner/model_request_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/sender.h"
#include "simpartner/sim/sim_node.h"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::sim {
namespace {

uint64_t BigEndian64(const uint8_t* bytes) {
  uint64_t value = 0;
  for (int i = 0; i < 8; ++i) value = (value << 8) | bytes[i];
  return value;
}

// Our own messages are read back at the rate they are sent (about one a
// second); a few queued are enough, since only a new id matters.
constexpr int kQueuedMessages = 8;

}  // namespace

std::optional<int64_t> PeekSimulationId(const std::string& channel, const void* data,
                                        size_t size) {
  int64_t hash = 0;
  if (channel == channels::kState) hash = state_t::getHash();
  else if (channel == channels::kStatus) hash = status_t::getHash();
  else if (channel == channels::kModel) hash = model_t::getHash();
  else return std::nullopt;
  constexpr size_t kIdEnd = 8 + 8 + 8;  // fingerprint, utime, simulation_id
  if (data == nullptr || size < kIdEnd) return std::nullopt;
  const auto* bytes = static_cast<const uint8_t*>(data);
  if (static_cast<int64_t>(BigEndian64(bytes)) != hash) return std::nullopt;
  return static_cast<int64_t>(BigEndian64(bytes + 16));
}

PeerWatch::PeerWatch(lcm::LCM* lcm, BusSigning* signing, BadMessageCounter* refused,
                     RefusalReport report)
    : lcm_(lcm), signing_(signing), refused_(refused), report_(std::move(report)) {
  // Not SIM_STATE: reading back its own 1 kHz state would wake the sim's
  // input wait every step (measured: ~190 steps a second then overran the
  // input budget). Every sim publishes SIM_STATUS at least once a second
  // and SIM_MODEL at start and on request, which is soon enough.
  for (const char* channel : {channels::kStatus, channels::kModel}) {
    lcm::Subscription* s = lcm_->subscribe(channel, &PeerWatch::OnMessage, this);
    s->setQueueCapacity(kQueuedMessages);
    subscriptions_.push_back(s);
  }
}

PeerWatch::~PeerWatch() {
  for (lcm::Subscription* s : subscriptions_) lcm_->unsubscribe(s);
}

void PeerWatch::AddOwnId(int64_t simulation_id) { own_ids_.insert(simulation_id); }

std::vector<OtherSimulation> PeerWatch::TakeNew() { return std::exchange(new_, {}); }

void PeerWatch::OnMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  std::string refusal;
  bool print = false;
  const std::optional<size_t> size =
      OpenFromBus(channel, buffer->data, static_cast<size_t>(buffer->data_size), signing_,
                  refused_, &refusal, &print);
  if (!size) {  // not from a holder of the key
    if (report_) report_(refusal, print);
    return;
  }
  const std::optional<int64_t> id = PeekSimulationId(channel, buffer->data, *size);
  if (!id || own_ids_.count(*id) != 0) return;
  // Forged ids come without end: remember a bounded number (a forgotten
  // id heard again is new again; reports are rate-limited by the caller).
  if (heard_ids_.size() >= kMaxRememberedIds) heard_ids_.clear();
  if (!heard_ids_.insert(*id).second) return;
  if (new_.size() < kMaxRememberedIds) new_.push_back(OtherSimulation{*id, channel});
}

std::optional<OtherSimulation> ProbeForOtherSimulation(lcm::LCM* lcm,
                                                       std::chrono::milliseconds wait,
                                                       BusSigning* signing) {
  PeerWatch watch(lcm, signing);
  model_request_t request{};
  request.utime = WallMicros();
  request.sender = SenderName("simpartner-sim");
  PublishSigned(lcm, channels::kModelRequest, request, signing);
  const auto end = std::chrono::steady_clock::now() + wait;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        end - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    lcm->handleTimeout(static_cast<int>(left.count()));
    std::vector<OtherSimulation> heard = watch.TakeNew();
    if (!heard.empty()) return heard.front();
  }
  return std::nullopt;
}

std::string DescribeOtherSimulation(const OtherSimulation& other, const std::string& url) {
  return "another simulation (id " + std::to_string(other.simulation_id) + ") publishes " +
         other.channel + " on " + url +
         ": both sims would apply every command, and viewers and loggers would see two "
         "simulations in turn. Give each sim its own bus (another port in --lcm-url, e.g. "
         "udpm://239.255.76.67:7668?ttl=0) or stop the other one";
}

}  // namespace simpartner::sim
