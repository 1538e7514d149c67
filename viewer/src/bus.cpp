#include "simpartner/viewer/bus.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "simpartner/bus_decode.h"
#include "simpartner/channels.h"
#include "simpartner/command_t.hpp"
#include "simpartner/control_t.hpp"
#include "simpartner/model_request_t.hpp"
#include "simpartner/sender.h"

namespace simpartner::viewer {
namespace {

constexpr auto kModelRequestInterval = std::chrono::milliseconds(500);
// Every decoded state is checked (so bad ones are counted), but only the
// newest is kept; the queue only has to hold what arrives between two
// drains (a frame), at up to 50x real time of a 1 kHz sim.
constexpr int kStateQueue = 2000;
// A flood that outpaces decoding must not starve drawing: past this, the
// rest waits for the next frame (or is dropped by the kernel, which is
// harmless for a stateless stream).
constexpr auto kMaxDrainOverrun = std::chrono::milliseconds(30);

}  // namespace

ViewerBus::ViewerBus(lcm::LCM* lcm, const std::string& url, Scene* scene, Reporter report,
                     BusSigning* signing, const std::string& program)
    : lcm_(*lcm),
      url_(url),
      scene_(scene),
      report_(std::move(report)),
      sender_(SenderName(program)),
      signing_(signing) {
  lcm_.subscribe(channels::kModel, &ViewerBus::OnModel, this)->setQueueCapacity(4);
  lcm_.subscribe(channels::kState, &ViewerBus::OnState, this)->setQueueCapacity(kStateQueue);
  lcm_.subscribe(channels::kStatus, &ViewerBus::OnStatus, this)->setQueueCapacity(100);
  lcm_.subscribe(channels::kSensor, &ViewerBus::OnSensor, this)->setQueueCapacity(1000);
  // A snapshot of a long run comes in many parts at once.
  lcm_.subscribe(channels::kSoilRuts, &ViewerBus::OnSoilRuts, this)->setQueueCapacity(1000);
}

int ViewerBus::Drain(Clock::time_point until) {
  int handled = 0;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    const int timeout = static_cast<int>(std::max<int64_t>(left.count(), 0));
    const int status = lcm_.handleTimeout(timeout);
    if (status < 0) {
      // A signal (SIGTERM, SIGINT: SDL turns them into a quit event) cut
      // the wait short: back to the frame loop, which sees the event.
      if (errno == EINTR) break;
      throw std::runtime_error("LCM at '" + url_ + "' failed while receiving: " +
                               std::strerror(errno));
    }
    if (status == 0) {
      if (Clock::now() >= until) break;
      continue;
    }
    ++handled;
    RequestModelIfNeeded();
    if (Clock::now() > until + kMaxDrainOverrun) break;
  }
  return handled;
}

void ViewerBus::Note(const Verdict& verdict) {
  if (verdict.want_model) want_model_ = true;
  if (!verdict.problem) return;
  const int64_t count = scene_->rejected(verdict.problem->kind);
  if (count == 1 || count % 1000 == 0)
    report_(verdict.problem->message + (count > 1 ? " (" + std::to_string(count) + " so far)" : ""));
}

template <class T>
bool ViewerBus::Decode(const lcm::ReceiveBuffer* buffer, const std::string& channel, T* out) {
  const auto received = static_cast<size_t>(buffer->data_size);
  const BusSigning::Opened opened = OpenMessage(signing_, channel, buffer->data, received);
  if (!opened.refusal.empty()) {
    // An unsigned, forged or replayed message: said at most once a second.
    scene_->CountUndecodable(channel,
                             std::to_string(received) + " bytes refused: " + opened.refusal);
    if (const auto line = signature_refusals_.CountSignatureRefusal(
            channel, DescribeSignatureRefusal(channel, received, opened.refusal), Clock::now()))
      report_(*line + "; ignored");
    return false;
  }
  if (const auto failure = DecodeLcm(buffer->data, opened.size, out)) {
    scene_->CountUndecodable(channel, std::to_string(opened.size) + " bytes refused as simpartner." +
                                          T::getTypeName() + ": " + failure->reason);
    Note(Verdict{false, scene_->recent_problems().back(), false});
    return false;
  }
  return true;
}

void ViewerBus::RequestModelIfNeeded() {
  if (!want_model_) return;
  const auto now = Clock::now();
  if (model_requests_ > 0 && now - last_request_ < kModelRequestInterval) return;
  model_request_t request{};
  request.utime = WallMicros();
  request.sender = sender_;
  PublishSigned(&lcm_, channels::kModelRequest, request, signing_);
  last_request_ = now;
  ++model_requests_;
  want_model_ = false;  // until a message shows it is still missing
}

void ViewerBus::OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  model_t model;
  if (!Decode(buffer, channel, &model)) return;
  const Verdict v = scene_->OfferModel(model);
  if (v.accepted) want_model_ = false;
  Note(v);
}

void ViewerBus::OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  state_t state;
  if (!Decode(buffer, channel, &state)) return;
  const Verdict verdict = scene_->OfferState(std::move(state));
  Note(verdict);
  if (verdict.accepted && state_listener_) state_listener_(*scene_->state());
}

void ViewerBus::OnStatus(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  status_t status;
  if (!Decode(buffer, channel, &status)) return;
  Note(scene_->OfferStatus(status));
}

void ViewerBus::OnSensor(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  sensor_reading_t reading;
  if (!Decode(buffer, channel, &reading)) return;
  Note(scene_->OfferSensorReading(reading));
}

void ViewerBus::OnSoilRuts(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  soil_ruts_t ruts;
  if (!Decode(buffer, channel, &ruts)) return;
  Note(scene_->OfferSoilRuts(ruts));
}

void ViewerBus::SendControl(int8_t action, int64_t steps, double speed) {
  control_t control{};
  control.utime = WallMicros();
  control.request_id = ++request_id_;
  // The keys act on the simulation on screen, not on another one that
  // might share the bus (0 = any, before a model is shown).
  control.simulation_id = scene_->has_model() ? scene_->model().simulation_id : 0;
  control.sender = sender_;
  control.action = action;
  control.steps = steps;
  control.speed = speed;
  PublishSigned(&lcm_, channels::kControl, control, signing_);
}

void ViewerBus::RequestScans() {
  if (!scene_->has_model()) return;
  const model_t& m = scene_->model();
  for (const sensor_t& sensor : m.sensors) {
    if (sensor.kind != sensor_t::KIND_SCANNER) continue;
    command_t command{};
    command.utime = WallMicros();
    command.request_id = ++request_id_;
    command.simulation_id = m.simulation_id;
    command.sender = sender_;
    if (sensor.robot >= 0 && sensor.robot < m.num_robots)
      command.robot = m.robots[static_cast<size_t>(sensor.robot)].name;
    command.target = sensor.name;
    command.action = command_t::ACTION_READ;
    command.apply_at_step = -1;
    PublishSigned(&lcm_, channels::kCommand, command, signing_);
  }
}

}  // namespace simpartner::viewer
