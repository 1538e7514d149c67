#include "simpartner/sim/sim_node.h"

#include <sys/select.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <iostream>

#include "simpartner/bus_decode.h"
#include "simpartner/bus_signing.h"
#include "simpartner/channels.h"
#include "simpartner/control_t.hpp"
#include "simpartner/message_checks.h"
#include "simpartner/model_request_t.hpp"
#include "simpartner/sender.h"
#include "simpartner/state_request_t.hpp"
#include "simpartner/sync_t.hpp"
#include "simpartner/text.h"

namespace simpartner::sim {
namespace {

constexpr size_t kRecentWarnings = 16;
// When the sim falls this far behind its schedule (a slow machine, a
// debugger), it re-anchors instead of racing to catch up.
constexpr auto kMaxLag = std::chrono::milliseconds(100);
// Input handled once a step is due: at most this much wall time, so that a
// flood of messages (every one refused, and answered) cannot stop the
// stepping; the rest waits in the socket for the next step.
constexpr auto kInputBudget = std::chrono::microseconds(200);
// Steps in one status period that left input waiting before the sim says so.
constexpr int64_t kDeferralsWorthAWarning = 100;
// Replies to refused commands sent in one second, at most.
constexpr int kRefusalRepliesPerSecond = 1000;
// Refused commands printed in full before printing thins out.
constexpr int64_t kPrintFirstRefusals = 100;

std::string FormatMs(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", ms);
  return text;
}

}  // namespace

MessageSizes MeasureMessages(const Simulation& sim) {
  model_t model;
  sim.FillModel(&model);
  state_t state;
  sim.FillState(&state);
  return {static_cast<size_t>(model.getEncodedSize()), static_cast<size_t>(state.getEncodedSize())};
}

void ReportMessageSizes(const MessageSizes& sizes, std::ostream& out) {
  out << "simpartner-sim: SIM_MODEL is " << sizes.model << " bytes, SIM_STATE " << sizes.state
      << " bytes\n";
  for (auto [channel, bytes] : {std::pair{channels::kModel, sizes.model},
                                std::pair{channels::kState, sizes.state}}) {
    if (bytes > kSafeMessageBytes)
      out << "simpartner-sim: warning: " << channel << " (" << bytes / 1024
          << " KiB) is above " << kSafeMessageBytes / 1024
          << " KiB: a receiver loses it unless its LCM URL raises the socket buffer "
             "(recv_buf_size=4194304 in its URL, as the logger does)\n";
  }
  out << std::flush;
}

std::string MessagesTooLarge(const MessageSizes& sizes) {
  std::string problems;
  for (auto [channel, bytes] : {std::pair{channels::kModel, sizes.model},
                                std::pair{channels::kState, sizes.state}}) {
    if (bytes <= kMaxMessageBytes) continue;
    problems += std::string(problems.empty() ? "" : "; ") + channel + " would be " +
                std::to_string(bytes) + " bytes (" + FormatNumber(bytes / 1048576.0, 4) +
                " MiB), more than the " + std::to_string(kMaxMessageBytes >> 20) +
                " MiB a receiver's socket buffer takes (a smaller heightfield, or fewer bodies)";
  }
  return problems;
}

SimNode::SimNode(Simulation* sim, lcm::LCM* lcm, int stop_fd, BusSigning* signing)
    : sim_(sim),
      lcm_(lcm),
      stop_fd_(stop_fd),
      signing_(signing),
      bus_sender_(lcm, signing),
      host_(HostName()),
      sender_(SenderName("simpartner-sim")),
      peers_(lcm, signing, &bad_message_counter_,
             [this](const std::string& line, bool print) { ReportBadMessageText(line, print); }) {
  peers_.AddOwnId(sim->simulation_id());
  paused_ = sim->params().startPaused;
  speed_ = sim->params().speed;
  lcm_->subscribe(channels::kCommand, &SimNode::OnCommand, this)->setQueueCapacity(1000);
  lcm_->subscribe(channels::kControl, &SimNode::OnControl, this)->setQueueCapacity(100);
  lcm_->subscribe(channels::kModelRequest, &SimNode::OnModelRequest, this)->setQueueCapacity(100);
  lcm_->subscribe(channels::kStateRequest, &SimNode::OnStateRequest, this)->setQueueCapacity(100);
  lcm_->subscribe(channels::kSync, &SimNode::OnSync, this)->setQueueCapacity(1000);
  last_status_time_ = Clock::now();
}

void SimNode::Warn(int8_t severity, const std::string& source, const std::string& message) {
  warning_t w{};
  w.step = sim_->step();
  w.severity = severity;
  w.source = source;
  w.message = message;
  Record(std::move(w));
}

void SimNode::Record(warning_t w) {
  std::cerr << "simpartner-sim: step " << w.step << ": " << w.source << ": " << w.message << "\n";
  ++warnings_total_;
  // The fault that paused the run stays in every status while it lasts,
  // however many warnings come after it.
  if (w.severity == warning_t::SEVERITY_ERROR && sim_->faulted()) fault_warning_ = w;
  recent_warnings_.push_back(std::move(w));
  if (recent_warnings_.size() > kRecentWarnings) recent_warnings_.pop_front();
  status_changed_ = true;
}

void SimNode::ReportBadMessage(const std::string& channel, const std::string& what) {
  ReportBadMessageText(channel + ": " + what, bad_message_counter_.Count(channel, what));
}

void SimNode::ReportBadMessageText(const std::string& description, bool print) {
  bad_messages_ = static_cast<int64_t>(bad_message_counter_.total());
  // A flood is counted in full but printed only now and then.
  if (print)
    Warn(warning_t::SEVERITY_WARNING, "bus",
         description + "; ignored (" + std::to_string(bad_messages_) + " bad so far: " +
             bad_message_counter_.Summary() + ")");
}

template <class T>
bool SimNode::DecodeInput(const lcm::ReceiveBuffer* buffer, const std::string& channel, T* out) {
  bool print = false;
  const auto refusal = DecodeSigned(channel, buffer->data, buffer->data_size, signing_, out,
                                    &bad_message_counter_, &print);
  if (!refusal) return true;
  ReportBadMessageText(*refusal, print);
  return false;
}

void SimNode::OnCommand(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  command_t command;
  if (!DecodeInput(buffer, channel, &command)) return;
  // Texts that are not UTF-8 or too long are refused as every reader of
  // SIM_COMMAND refuses them (message_checks.h), before the command's
  // meaning is judged; its sender cannot be answered by name.
  if (const auto problem = CheckCommand(command)) {
    ReportBadMessage(channel, problem->message);
    return;
  }
  SubmitCommand(command);
}

bool SimNode::MayAnswerRefusal() {
  // A flood of bad messages must not double itself into a flood of replies
  // (which every process on the bus, the sim included, would have to read).
  const auto now = Clock::now();
  if (now - refusal_window_start_ >= std::chrono::seconds(1)) {
    refusal_window_start_ = now;
    refusal_replies_in_window_ = 0;
  }
  if (refusal_replies_in_window_ >= kRefusalRepliesPerSecond) {
    ++refusal_replies_withheld_;
    return false;
  }
  ++refusal_replies_in_window_;
  return true;
}

void SimNode::SubmitCommand(const command_t& command) {
  if (auto rejection = sim_->Submit(command)) {
    ++commands_rejected_;
    // Every sender gets its reply; the terminal gets the first refusals
    // and then one in kPrintEvery, so a flood cannot drown it (or cost the
    // sim its time in writes).
    if (commands_rejected_ <= kPrintFirstRefusals ||
        commands_rejected_ % BadMessageCounter::kPrintEvery == 0)
      std::cerr << "simpartner-sim: step " << sim_->step() << ": command " << command.request_id
                << " from '" << command.sender << "' rejected: " << rejection->reason
                << (commands_rejected_ > kPrintFirstRefusals
                        ? " (" + std::to_string(commands_rejected_) +
                              " refused so far; only one in " +
                              std::to_string(BadMessageCounter::kPrintEvery) + " is printed)"
                        : std::string())
                << "\n";
    // Refusals are answered at up to kRefusalRepliesPerSecond.
    if (MayAnswerRefusal()) Publish(channels::kCommandReply, *rejection);
  }
}

void SimNode::OnControl(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  control_t control;
  if (!DecodeInput(buffer, channel, &control)) return;
  // A quit or reset meant for another system on the same bus is refused
  // like any bad message: counted, printed only now and then.
  if (control.simulation_id != 0 && control.simulation_id != sim_->simulation_id()) {
    ReportBadMessage(channel, "action " + std::to_string(control.action) + " from '" +
                                  control.sender + "' is for simulation_id " +
                                  std::to_string(control.simulation_id) + "; this is " +
                                  std::to_string(sim_->simulation_id()));
    return;
  }
  status_changed_ = true;
  // A control that changes the schedule ends the wait for the next step at
  // once (at a slow speed that wait can be long). One that changes nothing
  // (a repeated SET_SPEED or RESUME) leaves the schedule alone, so a stream
  // of them cannot make the sim step early.
  switch (control.action) {
    case control_t::ACTION_PAUSE:
      paused_ = true;
      steps_to_run_ = 0;
      wake_ = true;
      break;
    case control_t::ACTION_RESUME:
      if (paused_) {
        paused_ = false;
        schedule_anchored_ = false;
        wake_ = true;
      }
      break;
    case control_t::ACTION_STEP:
      if (control.steps < 1 || control.steps > 100000000) {
        ReportBadMessage(channel, "step count " + std::to_string(control.steps) +
                                      " from '" + control.sender + "' is out of range [1, 1e8]");
        return;
      }
      paused_ = true;
      steps_to_run_ = control.steps;
      wake_ = true;
      break;
    case control_t::ACTION_RESET:
      // The old simulation's last status says it was reset: followers
      // then take the next model, of the new id, as its successor
      // (simulation_follower.h), and a copy of the model as another sim.
      PublishStatus(status_t::RUN_RESET);
      sim_->Reset(WallMicros());
      lock_step_.Clear();  // they were synchronous with the old simulation
      peers_.AddOwnId(sim_->simulation_id());
      steps_to_run_ = 0;
      schedule_anchored_ = false;
      model_changed_ = true;
      wake_ = true;
      break;
    case control_t::ACTION_SET_SPEED:
      // Below kMinSpeed one step would take longer than a person waits
      // for a pause to take effect; <= 0 means as fast as possible.
      if (!std::isfinite(control.speed) || control.speed > kMaxSpeed ||
          (control.speed > 0 && control.speed < kMinSpeed)) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", control.speed);
        ReportBadMessage(channel, std::string("speed ") + text + " from '" + control.sender +
                                      "' is out of range (<= 0 for as fast as possible, or " +
                                      "0.001 to 1000 times real time)");
        return;
      }
      if (control.speed != speed_ && !(control.speed <= 0 && speed_ <= 0)) {
        speed_ = control.speed;
        schedule_anchored_ = false;
        wake_ = true;
      }
      break;
    case control_t::ACTION_QUIT:
      quit_ = true;
      wake_ = true;
      break;
    default:
      ReportBadMessage(channel, "unknown action " + std::to_string(control.action) + " from '" +
                                    control.sender + "'");
      return;
  }
}

void SimNode::OnModelRequest(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  model_request_t request;
  if (!DecodeInput(buffer, channel, &request)) return;
  model_requested_ = true;
}

void SimNode::OnStateRequest(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  state_request_t request;
  if (!DecodeInput(buffer, channel, &request)) return;
  if (request.simulation_id != 0 && request.simulation_id != sim_->simulation_id()) {
    ReportBadMessage(channel, "request from '" + request.sender + "' is for simulation_id " +
                                  std::to_string(request.simulation_id) + "; this is " +
                                  std::to_string(sim_->simulation_id()));
    return;
  }
  state_requested_ = true;
}

void SimNode::OnSync(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
  sync_t message;
  if (!DecodeInput(buffer, channel, &message)) return;
  if (message.simulation_id != 0 && message.simulation_id != sim_->simulation_id()) {
    ReportBadMessage(channel, "action " + std::to_string(message.action) + " of controller '" +
                                  message.controller + "' is for simulation_id " +
                                  std::to_string(message.simulation_id) + "; this is " +
                                  std::to_string(sim_->simulation_id()));
    return;
  }
  const int64_t step = sim_->step();
  // On a signed bus, the link the message verified from: a controller's
  // marks must come from its JOIN's.
  LockStep::Origin origin;
  if (signing_ != nullptr) origin.link = SigningLink(buffer->data, buffer->data_size);
  LockStep::Outcome outcome = lock_step_.Handle(message, step, origin);
  if (outcome.refused) ReportBadMessage(channel, outcome.reply->reason);
  if (outcome.reply && (!outcome.refused || MayAnswerRefusal())) {
    outcome.reply->simulation_id = sim_->simulation_id();
    Publish(channels::kSyncReply, *outcome.reply);
  }
  if (outcome.refused) return;
  if (message.action != sync_t::ACTION_DONE) status_changed_ = true;
  // A controller whose first tick is this very step needs its state, which
  // went out before it joined (or never: a paused sim at step 0).
  if (outcome.reply && outcome.reply->event == sync_reply_t::EVENT_JOINED &&
      outcome.reply->tick == step)
    state_requested_ = true;
  // The last answer awaited: stop waiting for input, step.
  if (message.action == sync_t::ACTION_DONE && lock_step_.WaitingOn(step).empty()) wake_ = true;
}

void SimNode::ReplyState() {
  const auto now = Clock::now();
  if (!state_requested_ || now - last_state_reply_ < std::chrono::milliseconds(1000 / kStateRepliesPerSecond))
    return;
  state_t state;
  sim_->FillState(&state);
  Publish(channels::kStateReply, state);
  state_requested_ = false;
  last_state_reply_ = now;
}

template <class T>
void SimNode::Publish(const char* channel, const T& message) {
  bus_sender_.Send(channel, message);
}

void SimNode::ReportSendOutcomes() {
  for (const BusSender::Outcome& outcome : bus_sender_.TakeOutcomes()) {
    if (outcome.sent) {
      Warn(warning_t::SEVERITY_INFO, "bus",
           "sending works again; " + std::to_string(failed_sends_in_outage_) +
               " messages could not be sent before (the first on " + first_failed_channel_ +
               ": " + first_send_error_ + ")");
      failed_sends_in_outage_ = 0;
      continue;
    }
    // A link down (a cable, a veth set down, no route) makes every send
    // fail: said on the first failure and then once a second, with the
    // count, so that the stepping goes on at its rate and the log says
    // what was lost.
    ++failed_sends_;
    if (failed_sends_in_outage_++ == 0) {
      first_failed_channel_ = outcome.channel;
      first_send_error_ = outcome.error;
    }
    const auto now = Clock::now();
    if (failed_sends_in_outage_ == 1 ||
        now - last_send_failure_report_ >= std::chrono::seconds(1)) {
      last_send_failure_report_ = now;
      Warn(warning_t::SEVERITY_ERROR, "bus",
           outcome.channel + ": send failed: " + outcome.error + " (" +
               std::to_string(failed_sends_in_outage_) + " failed since the last that went out, " +
               std::to_string(failed_sends_) + " in all)");
    }
  }
}

void SimNode::ReportOtherSimulations() {
  // The first other simulation in full at once; then at most one line per
  // kOtherSimulationReportPeriod, counting the ids heard meanwhile (50,000
  // forged ids once made 48,922 lines).
  for (const OtherSimulation& other : peers_.TakeNew()) {
    ++others_unreported_;
    last_other_ = other;
  }
  const auto now = Clock::now();
  if (others_unreported_ == 0 || now - last_other_report_ < kOtherSimulationReportPeriod) return;
  std::string text = DescribeOtherSimulation(last_other_, sim_->params().lcmUrl);
  if (others_unreported_ > 1)
    text += " (" + std::to_string(others_unreported_ - 1) + " more simulation ids heard since " +
            (others_reported_ ? "the last such line" : "the start") + ")";
  Warn(warning_t::SEVERITY_ERROR, "bus", text);
  others_unreported_ = 0;
  others_reported_ = true;
  last_other_report_ = now;
}

void SimNode::HandleIncoming(Clock::duration timeout) {
  // About to wait: what this step published goes out now, not at the
  // sending thread's next poll.
  if (timeout > Clock::duration::zero()) bus_sender_.Kick();
  const int fd = lcm_->getFileno();
  auto remaining = timeout;
  const auto end = Clock::now() + timeout;
  // Past the end (the step is due), input gets kInputBudget more; what is
  // still waiting then is handled before the next step.
  const auto budget_end = end + kInputBudget;
  wake_ = false;
  // Handle what is there, then wait for more until the timeout.
  while (true) {
    fd_set fds;
    FD_ZERO(&fds);
    FD_SET(fd, &fds);
    if (stop_fd_ >= 0) FD_SET(stop_fd_, &fds);
    const auto micros =
        std::max<int64_t>(0, std::chrono::duration_cast<std::chrono::microseconds>(remaining).count());
    timeval tv{static_cast<time_t>(micros / 1000000), static_cast<suseconds_t>(micros % 1000000)};
    const int ready = ::select(std::max(fd, stop_fd_) + 1, &fds, nullptr, nullptr, &tv);
    if (ready > 0 && stop_fd_ >= 0 && FD_ISSET(stop_fd_, &fds)) {
      quit_ = true;
      status_changed_ = true;
      return;
    }
    if (ready <= 0) return;  // timeout (or EINTR)
    const auto now = Clock::now();
    if (now >= budget_end) {
      ++input_deferrals_;
      return;
    }
    lcm_->handle();
    if (quit_ || wake_) return;
    remaining = end - Clock::now();
    if (remaining <= Clock::duration::zero()) remaining = Clock::duration::zero();
  }
}

void SimNode::ReportInputDeferrals() {
  // A message left for the next step now and then (a burst, a busy
  // machine) costs one step of latency and is not worth a warning; a
  // sustained flood is.
  if (input_deferrals_ - reported_deferrals_ < kDeferralsWorthAWarning) return;
  Warn(warning_t::SEVERITY_WARNING, "bus",
       "more input than the step budget (" +
           std::to_string(std::chrono::duration_cast<std::chrono::microseconds>(kInputBudget).count()) +
           " us past each due step): " + std::to_string(input_deferrals_ - reported_deferrals_) +
           " steps left messages waiting for the next step (" + std::to_string(input_deferrals_) +
           " since start; bad messages so far: " + std::to_string(bad_message_counter_.total()) +
           ", commands refused: " + std::to_string(commands_rejected_) +
           ", replies to refusals withheld beyond " + std::to_string(kRefusalRepliesPerSecond) +
           "/s: " + std::to_string(refusal_replies_withheld_) + ")");
  reported_deferrals_ = input_deferrals_;
}

void SimNode::CollectWarnings() {
  for (warning_t& w : sim_->TakeWarnings()) Record(std::move(w));
}

bool SimNode::WaitingForControllers() {
  const int64_t step = sim_->step();
  const std::vector<std::string> waiting = lock_step_.WaitingOn(step);
  if (waiting.empty()) {
    wait_tick_ = -1;
    for (const command_t& command : lock_step_.TakeAnswers(step)) SubmitCommand(command);
    return false;
  }
  const auto now = Clock::now();
  if (wait_tick_ != step) {
    wait_tick_ = step;
    wait_start_ = now;
  }
  const auto timeout = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(sim_->params().lockStepTimeout));
  if (now - wait_start_ < timeout) {
    HandleIncoming(std::min<Clock::duration>(timeout - (now - wait_start_),
                                             std::chrono::milliseconds(10)));
    return true;
  }
  // Never a silent hang: a controller that died, stalls or was cut off is
  // named and released, and the run goes on without it.
  const std::string reason = "no answer for tick " + std::to_string(step) + " within " +
                             FormatNumber(sim_->params().lockStepTimeout) +
                             " s (lockStepTimeout); from this tick on it is not synchronous";
  for (sync_reply_t& reply : lock_step_.ReleaseWaiting(step, reason)) {
    Warn(warning_t::SEVERITY_ERROR, "lockstep",
         "released controller '" + reply.controller + "' (" + reply.sender + ", period " +
             std::to_string(reply.period) + "): " + reason + "; the run goes on");
    reply.simulation_id = sim_->simulation_id();
    Publish(channels::kSyncReply, reply);
  }
  return WaitingForControllers();
}

void SimNode::PublishReplies() {
  for (const command_reply_t& reply : sim_->TakeReplies()) {
    ++commands_accepted_;
    Publish(channels::kCommandReply, reply);
  }
}

void SimNode::PublishPending() {
  ReportSendOutcomes();
  PublishReplies();
  for (const sensor_reading_t& reading : sim_->TakeSensorReadings())
    Publish(channels::kSensor, reading);
  CollectWarnings();
}

void SimNode::StepAndPublish() {
  const auto start = Clock::now();
  const bool ok = sim_->Step();
  const Clock::duration spent = Clock::now() - start;
  compute_time_ += spent;
  total_compute_time_ += spent;
  ++compute_steps_;
  ++steps_taken_;
  // What this step produced (replies, sensor readings, warnings) goes
  // before its state: a lock-step controller has all of it, the same in
  // every run, when its tick's state comes.
  PublishPending();
  if (!ok) {
    paused_ = true;
    steps_to_run_ = 0;
    status_changed_ = true;
    return;
  }
  if (sim_->step() % sim_->params().stateEvery == 0 || lock_step_.IsTick(sim_->step())) {
    sim_->FillState(&state_);
    Publish(channels::kState, state_);
  }
  PublishRutChanges();
}

void SimNode::StampRuts(soil_ruts_t* message) const {
  message->utime = WallMicros();
  message->simulation_id = sim_->simulation_id();
  message->step = sim_->step();
}

void SimNode::PublishRutChanges() {
  const int64_t period =
      std::max<int64_t>(1, std::llround(kRutPeriod / sim_->params().stepsize));
  if (sim_->step() % period != 0 || !sim_->ruts().has_changes()) return;
  soil_ruts_t changes = sim_->ruts().TakeChanges();
  StampRuts(&changes);
  Publish(channels::kSoilRuts, changes);
}

size_t SimNode::PublishRutSnapshot() {
  rut_parts_.clear();  // a newer snapshot, or none after a reset
  if (sim_->ruts().cells() == 0) return 0;
  size_t bytes = 0;
  for (soil_ruts_t& part : sim_->ruts().Snapshot()) {
    StampRuts(&part);
    bytes += static_cast<size_t>(part.getEncodedSize());
    rut_parts_.push_back(std::move(part));
  }
  PublishRutParts();
  return bytes;
}

void SimNode::PublishRutParts() {
  const auto now = Clock::now();
  if (rut_parts_.empty() || now < next_rut_part_) return;
  Publish(channels::kSoilRuts, rut_parts_.front());
  rut_parts_.pop_front();
  next_rut_part_ = now + kRutPartInterval;
}

size_t SimNode::PublishModel() {
  model_t model;
  sim_->FillModel(&model);
  model.host = host_;
  model.sender = sender_;
  Publish(channels::kModel, model);
  return static_cast<size_t>(model.getEncodedSize());
}

void SimNode::PublishStatus(std::optional<int8_t> run_state) {
  const auto now = Clock::now();
  const double wall = std::chrono::duration<double>(now - last_status_time_).count();
  if (wall > 0.05) {
    real_time_factor_ = static_cast<double>(sim_->step() - last_status_step_) *
                        sim_->params().stepsize / wall;
    if (real_time_factor_ < 0) real_time_factor_ = 0;  // after a reset
    last_status_time_ = now;
    last_status_step_ = sim_->step();
  }
  if (compute_steps_ > 0) {
    step_cost_ = std::chrono::duration<double>(compute_time_).count() / compute_steps_;
    compute_time_ = {};
    compute_steps_ = 0;
  }
  status_t status{};
  status.utime = WallMicros();
  status.simulation_id = sim_->simulation_id();
  status.host = host_;
  status.engine = sim_->params().engine;
  status.run_state = run_state         ? *run_state
                     : quit_           ? status_t::RUN_STOPPED
                     : sim_->faulted() ? status_t::RUN_FAULTED
                     : paused_         ? status_t::RUN_PAUSED
                                       : status_t::RUN_RUNNING;
  status.step = sim_->step();
  status.sim_time = sim_->time();
  status.real_time_factor = real_time_factor_;
  status.target_speed = speed_;
  status.step_cost = step_cost_;
  status.commands_accepted = commands_accepted_;
  status.commands_rejected = commands_rejected_;
  status.bad_messages = bad_messages_;
  status.warnings.assign(recent_warnings_.begin(), recent_warnings_.end());
  if (sim_->faulted() && fault_warning_ &&
      std::none_of(status.warnings.begin(), status.warnings.end(), [&](const warning_t& w) {
        return w.step == fault_warning_->step && w.message == fault_warning_->message;
      }))
    status.warnings.insert(status.warnings.begin(), *fault_warning_);
  status.num_warnings = static_cast<int16_t>(status.warnings.size());
  status.sync_controllers = lock_step_.Describe(sim_->step());
  status.num_sync_controllers = static_cast<int16_t>(status.sync_controllers.size());
  Publish(channels::kStatus, status);
  status_changed_ = false;
  if (progress_ != nullptr && now - last_progress_ >= kProgressEvery) {
    last_progress_ = now;
    char line[200];
    std::snprintf(line, sizeof line,
                  "simpartner-sim: sim time %.3f s (step %lld), real-time factor %.3f, %s", sim_->time(),
                  static_cast<long long>(sim_->step()), real_time_factor_,
                  quit_ ? "stopping" : sim_->faulted() ? "FAULTED (paused)" : paused_ ? "paused" : "running");
    *progress_ << line;
    if (commands_rejected_ > 0 || bad_messages_ > 0)
      *progress_ << ", " << commands_rejected_ << " commands refused, " << bad_messages_
                 << " bad messages";
    *progress_ << std::endl;
  }
}

void SimNode::PublishDue(Clock::time_point* next_model, Clock::time_point* next_status,
                         Clock::duration model_period, Clock::duration status_period) {
  ReplyState();
  PublishRutParts();
  const auto now = Clock::now();
  if (model_changed_ || ((model_requested_ || now >= *next_model) && now >= next_model_allowed_)) {
    const bool asked = model_changed_ || model_requested_;
    size_t sent = PublishModel();
    // A viewer that asks for the model (one started late) gets the ruts;
    // the periodic announcement leaves them out (they can be large). They
    // count against the same bytes a second.
    if (asked) sent += PublishRutSnapshot();
    const double bytes = static_cast<double>(sent);
    model_requested_ = model_changed_ = false;
    *next_model = now + model_period;
    next_model_allowed_ =
        now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                  std::max(1.0 / kModelRepliesPerSecond, bytes / kModelBytesPerSecond)));
  }
  if (status_changed_ || now >= *next_status) {
    if (now >= *next_status) ReportInputDeferrals();
    PublishStatus();
    *next_status = now + status_period;
  }
}

std::string SimNode::Summary() const {
  const double wall = std::chrono::duration<double>(Clock::now() - run_start_).count();
  const double sim_seconds = static_cast<double>(steps_taken_) * sim_->params().stepsize;
  const double step_us = steps_taken_ > 0 ? std::chrono::duration<double, std::micro>(
                                                total_compute_time_).count() / steps_taken_
                                          : 0.0;
  char text[400];
  std::snprintf(text, sizeof text,
                "simpartner-sim: ended at step %lld (sim time %.3f s); %lld steps in %.1f s of "
                "wall time (%.3f x real time overall), %.1f us of computing per step; commands "
                "%lld accepted, %lld refused; %lld bad messages; %lld warnings",
                static_cast<long long>(sim_->step()), sim_->time(),
                static_cast<long long>(steps_taken_), wall, wall > 0 ? sim_seconds / wall : 0.0,
                step_us, static_cast<long long>(commands_accepted_),
                static_cast<long long>(commands_rejected_), static_cast<long long>(bad_messages_),
                static_cast<long long>(warnings_total_));
  return text;
}

bool SimNode::WaitForDeadline() {
  // Real-time (or N x) pacing against absolute deadlines: the n-th step is
  // due at anchor + n * stepsize / speed, so waiting never drifts.
  const auto step_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(sim_->params().stepsize / speed_));
  const auto now = Clock::now();
  if (!schedule_anchored_ || now - next_deadline_ > kMaxLag) {
    if (schedule_anchored_) {
      // Sim time now lags wall time for good by this much: say so, since
      // anyone comparing the two (a logger, a real-robot log) must know.
      const double behind_ms = std::chrono::duration<double, std::milli>(now - next_deadline_).count();
      Warn(warning_t::SEVERITY_WARNING, "realtime",
           "fell " + FormatMs(behind_ms) +
               " ms behind real time (machine too slow, stalled or waiting for a lock-step "
               "controller); re-anchored, sim time now lags wall time by that much more");
    }
    next_deadline_ = now;
    schedule_anchored_ = true;
  }
  HandleIncoming(next_deadline_ > now ? next_deadline_ - now : Clock::duration::zero());
  if (wake_ && !quit_) return false;
  next_deadline_ += step_period;
  return true;
}

int SimNode::Run() {
  const Parameters& params = sim_->params();
  const int64_t last_step =
      params.duration > 0 ? static_cast<int64_t>(std::llround(params.duration / params.stepsize))
                          : -1;
  const auto model_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(params.modelPeriod));
  const auto status_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(params.statusPeriod));
  auto next_model = Clock::now();
  auto next_status = Clock::now();
  run_start_ = last_progress_ = Clock::now();
  PublishModel();
  int exit_status = 0;

  while (!quit_) {
    const bool stepping = !sim_->faulted() && (!paused_ || steps_to_run_ > 0);
    if (!stepping) wait_tick_ = -1;  // the lock-step timeout counts while stepping only
    if (stepping && WaitingForControllers()) {
      PublishDue(&next_model, &next_status, model_period, status_period);
      continue;
    }
    if (stepping && speed_ > 0 && !paused_) {
      if (!WaitForDeadline()) {
        // A control changed the schedule before this step was due: decide
        // again under the new one, publishing what changed.
        PublishPending();
        if (status_changed_) PublishStatus();
        continue;
      }
    } else if (stepping) {
      HandleIncoming(Clock::duration::zero());
    } else {
      HandleIncoming(std::chrono::milliseconds(10));
    }
    ReportOtherSimulations();
    if (quit_) break;
    const bool still_stepping = !sim_->faulted() && (!paused_ || steps_to_run_ > 0);
    if (still_stepping && !lock_step_.WaitingOn(sim_->step()).empty()) {
      // A controller joined while this step was due: it answers first.
      PublishDue(&next_model, &next_status, model_period, status_period);
      continue;
    }
    if (still_stepping) {
      StepAndPublish();
      if (steps_to_run_ > 0 && --steps_to_run_ == 0) status_changed_ = true;
      if (last_step >= 0 && sim_->step() >= last_step) quit_ = true;
    } else {
      PublishPending();
    }
    if (last_step >= 0 && sim_->faulted() && !quit_) {
      PublishPending();  // the fault's warning, with the status below
      std::cerr << "simpartner-sim: faulted at step " << sim_->step() << " of the " << last_step
                << " of --duration, which it cannot reach without a reset: ending (exit status "
                << kFaultedExitStatus << ")" << std::endl;
      exit_status = kFaultedExitStatus;
      quit_ = true;
    }
    PublishDue(&next_model, &next_status, model_period, status_period);
  }
  PublishStatus();  // RUN_STOPPED, with the fault among its warnings
  bus_sender_.Flush();
  return exit_status;
}

}  // namespace simpartner::sim
