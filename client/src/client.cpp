#include "simpartner/client/client.h"

#include <cmath>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <random>

#include "simpartner/bus_exposure.h"
#include "simpartner/bus_url.h"
#include "simpartner/channels.h"
#include "simpartner/control_t.hpp"
#include "simpartner/model_request_t.hpp"
#include "simpartner/sensor_t.hpp"
#include "simpartner/sender.h"
#include "simpartner/state_request_t.hpp"

namespace simpartner::client {
namespace {

template <class T>
std::vector<uint8_t> Encode(const T& message) {
  std::vector<uint8_t> bytes(static_cast<size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

constexpr size_t kMaxKeptReplies = 4096;
constexpr size_t kMaxKeptSyncReplies = 64;
// Colour and depth of a few cameras; older images are of no use.
constexpr int kImageQueue = 8;

// The bus key (bus_signing.h): the user's, SIMPARTNER_BUS_KEY's, or none.
std::optional<BusSigning> SigningFromEnvironment() {
  try {
    return BusSigning::FromEnvironment(
        [](const std::string& line) { std::cerr << "simpartner client: " << line << "\n"; });
  } catch (const BusKeyError& e) {
    throw ClientError(e.what());
  }
}

}  // namespace

Client::Client(ClientOptions options)
    : options_(std::move(options)),
      sender_(SenderName(options_.program)),
      images_(&bad_messages_,
              [](const std::string& line) { std::cerr << "simpartner client: " << line << "\n"; }),
      signing_(SigningFromEnvironment()) {
  // Two clients of one process share the sender; request ids starting at a
  // random point keep their replies apart.
  std::random_device random;
  next_request_id_ = (static_cast<int64_t>(random()) << 20) + 1;
  // A large socket buffer (unless the URL sets one): a reply must not be
  // dropped behind a burst of states from a sim running flat out.
  lcm_ = std::make_unique<lcm::LCM>(WithReceiveBuffer(options_.url));
  if (!lcm_->good())
    throw ClientError("cannot open the LCM bus '" + options_.url +
                      "' (expected e.g. udpm://239.255.76.67:7667?ttl=0)");
  if (const std::string open = BusExposureWarning(options_.url, signing_.has_value());
      !open.empty())
    std::cerr << "simpartner client: warning: " << open << "\n";
  for (const char* channel : {channels::kModel, channels::kState, channels::kStateReply,
                              channels::kStatus, channels::kCommandReply, channels::kSensor,
                              channels::kSyncReply}) {
    lcm::Subscription* subscription = lcm_->subscribe(
        channel, &Client::OnMessageBuffer, this);
    subscription->setQueueCapacity(1000);
  }
  if (options_.simulation_id != 0) follower_.Attach(options_.simulation_id, Clock::now());
  receiver_ = std::thread([this] { ReceiveLoop(); });
  if (options_.learn_model) {
    try {
      const int64_t wanted = options_.simulation_id;
      LearnModel(options_.model_timeout,
                 [wanted](const model_t& m) { return wanted == 0 || m.simulation_id == wanted; });
    } catch (...) {
      stop_ = true;
      receiver_.join();
      throw;
    }
  }
}

Client::~Client() {
  stop_ = true;
  if (receiver_.joinable()) receiver_.join();
}

void Client::OnMessageBuffer(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  OnMessage(buffer->data, buffer->data_size, channel);
}

void Client::ReceiveLoop() {
  while (!stop_) {
    if (lcm_->handleTimeout(50) < 0) {
      // A broken socket: stop receiving rather than spin; waits then time out.
      std::cerr << "simpartner client: receiving on " << options_.url << " failed\n";
      return;
    }
  }
}

void Client::OnMessage(const void* data, size_t size, const std::string& channel) {
  bool print = false;
  {
    // With a key, only signed messages; without, a signature is dropped.
    std::lock_guard<std::mutex> lock(mutex_);
    std::string refusal;
    const std::optional<size_t> message =
        OpenFromBus(channel, data, size, signing_ ? &*signing_ : nullptr, &bad_messages_,
                    &refusal, &print, &signing_mismatch_);
    if (!message) {
      if (print) std::cerr << "simpartner client: " << refusal << "\n";
      return;
    }
    size = *message;
  }
  // Counts a message that decodes but does not fit the model it claims.
  auto nonsense = [&](const std::string& what) {
    const std::string description = channel + ": " + what + "; ignored";
    if (bad_messages_.Count(channel, description))
      std::cerr << "simpartner client: " << description << "\n";
  };
  auto refused = [&](const std::optional<std::string>& why) {
    if (why && print) std::cerr << "simpartner client: " << *why << "\n";
    return why.has_value();
  };
  if (channel == channels::kModel) {
    auto model = std::make_shared<model_t>();
    std::lock_guard<std::mutex> lock(mutex_);
    if (refused(DecodeFromBus(channel, data, size, model.get(), &bad_messages_, &print))) return;
    if (const auto problem = CheckModel(*model)) {
      nonsense("model of simulation " + std::to_string(model->simulation_id) + ": " +
               problem->message);
      return;
    }
    // Another simulation's model (a second sim on the bus, a stale or
    // forged one) is not a restart of ours (simulation_follower.h).
    if (follower_.OnModel(model->simulation_id, Clock::now()) ==
        SimulationFollower::Verdict::kOther) {
      nonsense("model of another simulation (id " + std::to_string(model->simulation_id) +
               " from '" + model->sender + "') while simulation " +
               std::to_string(follower_.followed()) + " runs");
      return;
    }
    std::shared_ptr<const Catalog> catalog;
    if (catalog_ && model->simulation_id == catalog_->simulation_id()) {
      catalog = catalog_;  // the periodic announcement of the model we have
    } else {
      try {
        catalog = std::make_shared<const Catalog>(Catalog::FromModel(*model));
      } catch (const ClientError& e) {
        nonsense(e.what());
        return;
      }
    }
    newest_model_ = model;
    newest_catalog_ = catalog;
    ++model_count_;
    NoteSimulation(model->simulation_id);
    changed_.notify_all();
    step_changed_.notify_all();
  } else if (channel == channels::kState || channel == channels::kStateReply) {
    state_t state;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (refused(DecodeFromBus(channel, data, size, &state, &bad_messages_, &print))) return;
      last_heard_ = Clock::now();  // a sim is there, whichever
      if (!HeardFromAttached(state.simulation_id)) return;
      if (!AcceptState(state, channel)) return;
    }
    if (channel == channels::kStateReply) return;  // a repeated step: no callback
    std::lock_guard<std::mutex> callback_lock(callback_mutex_);
    if (on_state_ && catalog_known_) on_state_(state);
  } else if (channel == channels::kStatus) {
    status_t status;
    std::lock_guard<std::mutex> lock(mutex_);
    if (refused(DecodeFromBus(channel, data, size, &status, &bad_messages_, &print))) return;
    if (const auto problem = CheckStatus(status)) {
      nonsense(problem->message);
      return;
    }
    last_heard_ = Clock::now();
    if (!HeardFromAttached(status.simulation_id)) return;  // not our sim's status
    if (EndsSimulation(status.run_state)) follower_.Ended(status.simulation_id);
    status_ = status;
    ++status_count_;
    changed_.notify_all();
  } else if (channel == channels::kCommandReply) {
    command_reply_t reply;
    std::lock_guard<std::mutex> lock(mutex_);
    if (refused(DecodeFromBus(channel, data, size, &reply, &bad_messages_, &print))) return;
    if (reply.sender != sender_) return;  // every client sees every reply
    if (const auto problem = CheckCommandReply(reply)) {
      nonsense(problem->message);
      return;
    }
    replies_[reply.request_id] = reply;
    while (replies_.size() > kMaxKeptReplies) replies_.erase(replies_.begin());
    changed_.notify_all();
  } else if (channel == channels::kSyncReply) {
    sync_reply_t reply;
    std::lock_guard<std::mutex> lock(mutex_);
    if (refused(DecodeFromBus(channel, data, size, &reply, &bad_messages_, &print))) return;
    if (reply.sender != sender_) return;  // every client sees every reply
    sync_replies_.push_back(std::move(reply));
    while (sync_replies_.size() > kMaxKeptSyncReplies) sync_replies_.pop_front();
    changed_.notify_all();
    step_changed_.notify_all();
  } else if (channel == channels::kSensor) {
    sensor_reading_t reading;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (refused(DecodeFromBus(channel, data, size, &reading, &bad_messages_, &print))) return;
      if (!catalog_ || reading.simulation_id != catalog_->simulation_id()) return;
      if (const auto problem = CheckSensorReading(reading, &outline_)) {
        nonsense(problem->message);
        return;
      }
      readings_[reading.sensor] = reading;
      changed_.notify_all();
    }
    std::lock_guard<std::mutex> callback_lock(callback_mutex_);
    if (on_reading_) on_reading_(reading);
  } else if (channel == channels::kImage) {
    std::lock_guard<std::mutex> lock(mutex_);
    // Only a state of the model's simulation says how far it has come.
    const bool current = state_ && catalog_ && state_->simulation_id == catalog_->simulation_id();
    if (images_.Offer(data, size, current ? state_->step : -1)) changed_.notify_all();
  }
}

bool Client::AcceptState(const state_t& state, const std::string& channel) {
  // Another simulation's states (a new one announces itself with SIM_MODEL
  // first) and states that do not fit the model are not the state of the
  // sim we talk to.
  if (catalog_ && state.simulation_id != catalog_->simulation_id()) return false;
  if (const auto problem = CheckState(state, catalog_ ? &outline_ : nullptr)) {
    const std::string description = channel + ": " + problem->message + "; ignored";
    if (bad_messages_.Count(channel, description))
      std::cerr << "simpartner client: " << description << "\n";
    return false;
  }
  const bool reply = channel == channels::kStateReply;
  if (reply) {
    state_reply_ = state;
    ++state_reply_count_;
  }
  // A reply may overtake the SIM_STATE of its own step: it never replaces
  // a newer state of the same simulation.
  if (!reply || !state_ || state_->simulation_id != state.simulation_id ||
      state.step >= state_->step) {
    state_ = state;
    images_.StateSeen(state.step);
  }
  changed_.notify_all();
  step_changed_.notify_all();
  return true;
}

bool Client::HeardFromAttached(int64_t simulation_id) {
  if (follower_.followed() == 0) follower_.Attach(simulation_id, Clock::now());
  follower_.Heard(simulation_id, Clock::now());
  return follower_.WasFollowed(simulation_id);  // late messages of a reset one too
}

void Client::NoteSimulation(int64_t simulation_id) {
  latest_simulation_id_ = simulation_id;
  if (!catalog_ || simulation_id == catalog_->simulation_id()) return;
  if (!restart_ || restart_->new_simulation_id() != simulation_id)
    restart_.emplace(catalog_->simulation_id(), simulation_id);
}

void Client::ThrowIfRestarted() const {
  if (restart_) throw *restart_;
}

std::shared_ptr<const Catalog> Client::LearnModel(
    double timeout, const std::function<bool(const model_t&)>& accept) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  uint64_t seen;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    seen = model_count_;
  }
  RequestModel();
  auto next_request = Clock::now() + std::chrono::milliseconds(500);
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    if (model_count_ != seen && newest_model_ && accept(*newest_model_)) break;
    const auto now = Clock::now();
    if (now >= deadline) throw NoSim(options_.url, timeout, signing_mismatch_.Hint());
    if (now >= next_request) {
      // A request can be lost on a busy bus: ask again.
      lock.unlock();
      RequestModel();
      lock.lock();
      next_request = now + std::chrono::milliseconds(500);
      continue;
    }
    changed_.wait_until(lock, std::min(deadline, next_request));
  }
  const std::shared_ptr<const Catalog> catalog = newest_catalog_;
  model_ = newest_model_;
  outline_ = OutlineOf(*model_);
  catalog_ = catalog;
  catalog_known_ = true;
  readings_.clear();
  images_.SetModel(model_);
  replies_.clear();
  // Followed; unless a still newer sim has shown up meanwhile.
  restart_.reset();
  if (latest_simulation_id_ != 0 && latest_simulation_id_ != catalog->simulation_id())
    restart_.emplace(catalog->simulation_id(), latest_simulation_id_);
  return catalog;
}

std::shared_ptr<const Catalog> Client::Relearn(double timeout) {
  return LearnModel(timeout, [](const model_t&) { return true; });
}

std::shared_ptr<const Catalog> Client::catalog() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return catalog_ ? catalog_ : std::make_shared<const Catalog>();
}

std::shared_ptr<const model_t> Client::model() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return model_;
}

Target Client::Find(const std::string& name_or_port) const {
  std::lock_guard<std::mutex> lock(mutex_);
  ThrowIfRestarted();
  if (!catalog_) throw NoSim(options_.url, 0.0);
  return catalog_->Resolve(name_or_port);
}

void Client::Publish(const std::string& channel, const void* data, int size) {
  std::lock_guard<std::mutex> lock(publish_mutex_);
  std::vector<uint8_t> signed_bytes;
  if (signing_) {
    signed_bytes = signing_->Sign(channel, data, static_cast<size_t>(size));
    data = signed_bytes.data();
    size = static_cast<int>(signed_bytes.size());
  }
  if (lcm_->publish(channel, data, static_cast<unsigned>(size)) != 0)
    throw ClientError("publishing on " + channel + " failed (" + options_.url + ")");
}

void Client::RequestModel() {
  model_request_t request{};
  request.utime = WallMicros();
  request.sender = sender_;
  const std::vector<uint8_t> bytes = Encode(request);
  Publish(channels::kModelRequest, bytes.data(), static_cast<int>(bytes.size()));
}

int64_t Client::LockStepTick() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return lock_step_controller_.empty() ? -1 : lock_step_tick_;
}

void Client::PublishSync(sync_t message) {
  message.utime = WallMicros();
  message.sender = sender_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    message.simulation_id = options_.any_simulation || !catalog_ ? 0 : catalog_->simulation_id();
  }
  message.num_commands = static_cast<int32_t>(message.commands.size());
  const std::vector<uint8_t> bytes = Encode(message);
  Publish(channels::kSync, bytes.data(), static_cast<int>(bytes.size()));
}

std::optional<sync_reply_t> Client::TakeSyncReply(const std::string& controller) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = sync_replies_.begin(); it != sync_replies_.end(); ++it) {
    if (it->controller != controller) continue;
    sync_reply_t reply = std::move(*it);
    sync_replies_.erase(it);
    return reply;
  }
  return std::nullopt;
}

std::optional<state_t> Client::WaitForStepOrSyncReply(int64_t step, Clock::duration wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  const size_t replies = sync_replies_.size();
  step_changed_.wait_for(lock, wait, [&] {
    return restart_ || (state_ && state_->step >= step) || sync_replies_.size() != replies;
  });
  ThrowIfRestarted();
  if (state_ && state_->step >= step) return state_;
  return std::nullopt;
}

void Client::EnterLockStep(const std::string& controller, int64_t tick) {
  std::lock_guard<std::mutex> lock(mutex_);
  lock_step_controller_ = controller;
  lock_step_tick_ = tick;
  lock_step_queue_.clear();
}

std::vector<command_t> Client::TakeLockStepCommands(int64_t next_tick) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<command_t> commands;
  commands.swap(lock_step_queue_);
  lock_step_tick_ = next_tick;
  return commands;
}

void Client::LeaveLockStep() {
  std::lock_guard<std::mutex> lock(mutex_);
  lock_step_controller_.clear();
  lock_step_tick_ = -1;
  lock_step_queue_.clear();
}

void Client::PublishStateRequest() {
  state_request_t request{};
  request.utime = WallMicros();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    request.simulation_id = options_.any_simulation || !catalog_ ? 0 : catalog_->simulation_id();
  }
  request.sender = sender_;
  const std::vector<uint8_t> bytes = Encode(request);
  Publish(channels::kStateRequest, bytes.data(), static_cast<int>(bytes.size()));
}

state_t Client::RequestState(double timeout) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  uint64_t seen;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!catalog_) throw NoSim(options_.url, 0.0);
    ThrowIfRestarted();
    seen = state_reply_count_;
  }
  for (;;) {
    PublishStateRequest();
    const Clock::time_point again = std::min(deadline, Clock::now() + std::chrono::milliseconds(250));
    std::unique_lock<std::mutex> lock(mutex_);
    if (changed_.wait_until(lock, again, [&] { return state_reply_count_ != seen || restart_; })) {
      ThrowIfRestarted();
      return *state_reply_;
    }
    if (Clock::now() >= deadline)
      throw Timeout("SIM_STATE_REPLY to a SIM_STATE_REQUEST", timeout, options_.url,
                    signing_mismatch_.Hint());
  }
}

int64_t Client::Send(command_t command) {
  command.utime = WallMicros();
  command.sender = sender_;
  command.num_values = static_cast<int32_t>(command.values.size());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ThrowIfRestarted();
    command.request_id = next_request_id_++;
    command.simulation_id =
        options_.any_simulation || !catalog_ ? 0 : catalog_->simulation_id();
    if (!lock_step_controller_.empty()) {
      lock_step_queue_.push_back(command);
      return command.request_id;
    }
  }
  const std::vector<uint8_t> bytes = Encode(command);
  Publish(channels::kCommand, bytes.data(), static_cast<int>(bytes.size()));
  return command.request_id;
}

int64_t Client::Send(const std::string& target, int action, const std::string& text,
                     int64_t apply_at_step) {
  return Send(BuildCommandFromText(Find(target), action, text, apply_at_step));
}

command_reply_t Client::Command(command_t command, double timeout) {
  if (LockStepTick() >= 0)
    throw ClientError("a command cannot wait for its reply in lock-step: the sim replies when "
                      "it steps, and it waits for this controller's answer; Send it, and "
                      "LockStep::Next reports a refusal");
  if (timeout < 0) timeout = options_.reply_timeout;
  const std::string target = command.target.empty() ? "port " + std::to_string(command.port)
                                                     : command.target;
  const int64_t id = Send(std::move(command));
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    const auto it = replies_.find(id);
    if (it != replies_.end()) {
      command_reply_t reply = it->second;
      replies_.erase(it);
      if (!reply.accepted) throw Refused(target, reply.reason, id);
      return reply;
    }
    ThrowIfRestarted();
    if (changed_.wait_until(lock, deadline) == std::cv_status::timeout &&
        replies_.count(id) == 0)
      throw Timeout("reply from the sim to the command for " + target + " (request " +
                        std::to_string(id) + ")",
                    timeout, options_.url, signing_mismatch_.Hint());
  }
}

command_reply_t Client::Command(const std::string& target, int action, const std::string& text,
                                int64_t apply_at_step, double timeout) {
  return Command(BuildCommandFromText(Find(target), action, text, apply_at_step), timeout);
}

std::optional<command_reply_t> Client::TakeReply(int64_t request_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = replies_.find(request_id);
  if (it == replies_.end()) return std::nullopt;
  command_reply_t reply = it->second;
  replies_.erase(it);
  return reply;
}

void Client::SendControl(int action, int64_t steps, double speed) {
  control_t control{};
  control.utime = WallMicros();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    control.request_id = next_request_id_++;
    control.simulation_id = options_.any_simulation ? 0 : follower_.followed();
  }
  control.sender = sender_;
  control.action = static_cast<int8_t>(action);
  control.steps = steps;
  control.speed = speed;
  const std::vector<uint8_t> bytes = Encode(control);
  Publish(channels::kControl, bytes.data(), static_cast<int>(bytes.size()));
}

void Client::Pause() { SendControl(control_t::ACTION_PAUSE, 0, 0); }
void Client::Resume() { SendControl(control_t::ACTION_RESUME, 0, 0); }
void Client::Quit() { SendControl(control_t::ACTION_QUIT, 0, 0); }

void Client::Step(int64_t steps) {
  if (steps < 1 || steps > 100000000)
    throw BadValues("SIM_CONTROL", "steps", std::to_string(steps), "expected 1 to 100000000");
  SendControl(control_t::ACTION_STEP, steps, 0);
}

void Client::SetSpeed(double real_time_factor) {
  if (!std::isfinite(real_time_factor) || real_time_factor > 1000 ||
      (real_time_factor > 0 && real_time_factor < 0.001))
    throw BadValues("SIM_CONTROL", "speed", std::to_string(real_time_factor),
                    "expected <= 0 (as fast as possible) or 0.001 to 1000 times real time");
  SendControl(control_t::ACTION_SET_SPEED, 0, real_time_factor);
}

std::shared_ptr<const Catalog> Client::Reset(double timeout) {
  int64_t old_id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (catalog_) old_id = catalog_->simulation_id();
  }
  SendControl(control_t::ACTION_RESET, 0, 0);
  return LearnModel(timeout, [old_id](const model_t& m) { return m.simulation_id != old_id; });
}

std::optional<state_t> Client::LatestState() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return state_;
}

std::string Client::SigningHint() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return signing_mismatch_.Hint();
}

std::optional<status_t> Client::LatestStatus() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return status_;
}

std::optional<sensor_reading_t> Client::LatestReading(const std::string& sensor) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!catalog_) return std::nullopt;
  const Target& target = catalog_->Resolve(sensor);
  if (!target.is_sensor())
    throw UnknownTarget(sensor, {}, "'" + sensor + "' is an actuator, not a sensor");
  const auto it = readings_.find(target.index);
  if (it == readings_.end()) return std::nullopt;
  return it->second;
}

sensor_reading_t Client::WaitForReading(const std::string& sensor, int64_t after_step,
                                        double timeout) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  std::unique_lock<std::mutex> lock(mutex_);
  ThrowIfRestarted();
  if (!catalog_) throw NoSim(options_.url, 0.0);
  const Target target = catalog_->Resolve(sensor);
  if (!target.is_sensor())
    throw UnknownTarget(sensor, {}, "'" + sensor + "' is an actuator, not a sensor");
  for (;;) {
    ThrowIfRestarted();
    const auto it = readings_.find(target.index);
    if (it != readings_.end() && it->second.step > after_step) return it->second;
    if (changed_.wait_until(lock, deadline) == std::cv_status::timeout) {
      const auto again = readings_.find(target.index);
      if (again != readings_.end() && again->second.step > after_step) return again->second;
      throw Timeout("SIM_SENSOR reading of " + target.name + " after step " +
                        std::to_string(after_step),
                    timeout, options_.url, signing_mismatch_.Hint());
    }
  }
}

int Client::CameraIndex(const std::string& camera) {
  int index = -1;
  bool subscribe = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!catalog_) throw NoSim(options_.url, 0.0);
    const Target& target = catalog_->Resolve(camera);
    if (!target.is_sensor() || target.lcm_kind != sensor_t::KIND_CAMERA)
      throw UnknownTarget(camera, {}, "'" + camera + "' is a " + target.kind_name() +
                                          ", not a camera");
    index = target.index;
    subscribe = !images_subscribed_;
    images_subscribed_ = true;
  }
  // Outside mutex_: LCM holds its own lock while our handler takes mutex_.
  if (subscribe)
    lcm_->subscribe(channels::kImage, &Client::OnMessageBuffer, this)
        ->setQueueCapacity(kImageQueue);
  return index;
}

std::optional<image_t> Client::LatestImage(const std::string& camera, ImageKind kind) {
  const int index = CameraIndex(camera);
  std::lock_guard<std::mutex> lock(mutex_);
  return images_.Latest(index, kind);
}

image_t Client::WaitForImage(const std::string& camera, int64_t after_step, double timeout,
                             ImageKind kind) {
  const int index = CameraIndex(camera);
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  std::unique_lock<std::mutex> lock(mutex_);
  auto arrived = [&] { return images_.LatestStep(index, kind) > after_step; };
  for (;;) {
    ThrowIfRestarted();
    if (arrived()) return *images_.Latest(index, kind);
    if (changed_.wait_until(lock, deadline) == std::cv_status::timeout) {
      if (arrived()) return *images_.Latest(index, kind);
      throw Timeout(std::string("SIM_IMAGE ") + (kind == ImageKind::kColour ? "colour" : "depth") +
                        " image of " + camera + " after step " + std::to_string(after_step) +
                        " (is simpartner-camera running?)",
                    timeout, options_.url, signing_mismatch_.Hint());
    }
  }
}

state_t Client::WaitUntilSimTime(double sim_time, double timeout) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  std::unique_lock<std::mutex> lock(mutex_);
  if (!catalog_) throw NoSim(options_.url, 0.0);
  const double tolerance = catalog_->step_size() / 2;
  auto reached = [&] {
    return state_ && state_->simulation_id == catalog_->simulation_id() &&
           state_->sim_time >= sim_time - tolerance;
  };
  for (;;) {
    ThrowIfRestarted();
    if (reached()) return *state_;
    if (changed_.wait_until(lock, deadline) == std::cv_status::timeout) {
      if (reached()) return *state_;
      char text[64];
      std::snprintf(text, sizeof text, "%g", sim_time);
      throw Timeout(std::string("SIM_STATE at sim time ") + text + " s" +
                        (state_ ? " (the sim is at " + std::to_string(state_->sim_time) + " s)"
                                : std::string(" (no SIM_STATE yet)")),
                    timeout, options_.url, signing_mismatch_.Hint());
    }
  }
}

status_t Client::WaitForStatus(double timeout) {
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t seen = status_count_;
  if (!changed_.wait_until(lock, deadline, [&] { return status_count_ != seen; }))
    throw Timeout("SIM_STATUS", timeout, options_.url, signing_mismatch_.Hint());
  return *status_;
}

void Client::OnState(std::function<void(const state_t&)> callback) {
  std::lock_guard<std::mutex> lock(callback_mutex_);
  on_state_ = std::move(callback);
}

void Client::OnReading(std::function<void(const sensor_reading_t&)> callback) {
  std::lock_guard<std::mutex> lock(callback_mutex_);
  on_reading_ = std::move(callback);
}

double Client::SecondsSinceHeard() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!last_heard_) return std::numeric_limits<double>::infinity();
  return std::chrono::duration<double>(Clock::now() - *last_heard_).count();
}

std::optional<SimRestarted> Client::PendingRestart() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return restart_;
}

std::string Client::BadMessageSummary() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bad_messages_.Summary();
}

}  // namespace simpartner::client
