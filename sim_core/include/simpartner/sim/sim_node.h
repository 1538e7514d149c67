// The physics process on the bus: runs a Simulation against absolute
// deadlines (or as fast as possible), publishes SIM_STATE, SIM_SENSOR,
// SIM_COMMAND_REPLY, SIM_MODEL (at start, every modelPeriod and on request),
// SIM_STATE_REPLY (on request, running or paused), SIM_STATUS (every
// statusPeriod and on every change) and SIM_SOIL_RUTS (the ruts' changes
// every kRutPeriod of sim time; all of them with a model sent at start,
// on request or after a reset), and obeys SIM_COMMAND and SIM_CONTROL.
// Everything it publishes goes out, in order, through a sending thread
// (bus_sender.h). Synchronous controllers join over SIM_SYNC
// (lock_step.h): at each of their ticks the node waits for their answers
// before the next step. Undecodable messages are counted and reported,
// never acted on.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <ostream>
#include <string>

#include "simpartner/bus_decode.h"
#include "simpartner/sim/bus_sender.h"
#include "simpartner/sim/lock_step.h"
#include "simpartner/sim/peer_watch.h"
#include "simpartner/sim/simulation.h"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"

namespace simpartner::sim {

class SimNode {
 public:
  using Clock = std::chrono::steady_clock;

  // lcm must be good(); sim and lcm outlive the node. stop_fd, if >= 0,
  // becomes readable when the process is told to stop (a signalfd for
  // SIGINT/SIGTERM): the node then ends as on SIM_CONTROL quit, with a
  // last SIM_STATUS saying RUN_STOPPED.
  // `signing` (may be null: an unsigned bus) outlives the node: with it,
  // every message is signed and every input must be (bus_signing.h).
  SimNode(Simulation* sim, lcm::LCM* lcm, int stop_fd = -1, BusSigning* signing = nullptr);
  SimNode(const SimNode&) = delete;
  SimNode& operator=(const SimNode&) = delete;

  // Runs until SIM_CONTROL quit, stop_fd or the duration parameter.
  // Returns the process exit status: 0, or kFaultedExitStatus when a
  // duration was set and the health check (or the engine) faulted the run first:
  // a faulted sim takes no step until a reset, so its duration would never
  // come.
  int Run();
  static constexpr int kFaultedExitStatus = 4;  // 2: bad input, 3: another sim

  // Pieces of Run for tests: handle what arrived (waiting at most
  // timeout), then one step with its publications.
  void HandleIncoming(Clock::duration timeout);
  void StepAndPublish();
  // Returns the bytes it published.
  size_t PublishModel();
  // SIM_SOIL_RUTS: every rut cell (when there are any), in parts, the
  // first now and one every kRutPartInterval after it. Returns the bytes.
  size_t PublishRutSnapshot();
  // The ruts' changes go out every this much sim time while wheels press soil.
  static constexpr double kRutPeriod = 0.1;  // [s]
  // Parts of a snapshot sent at once (up to 98 kB each; 8 for a 100 m
  // track) overflowed a receiver's default socket buffer and were lost.
  static constexpr std::chrono::milliseconds kRutPartInterval{50};
  // The status now; `run_state` instead of the one the sim is in (the
  // old simulation's RUN_RESET).
  void PublishStatus(std::optional<int8_t> run_state = std::nullopt);

  // Real-time factors a SIM_CONTROL may ask for (besides <= 0: as fast as
  // possible).
  static constexpr double kMinSpeed = 1e-3;
  static constexpr double kMaxSpeed = 1000.0;
  // State requests are answered at most this often (a 40-byte request
  // returns a whole state); requests in between share the next answer.
  static constexpr int kStateRepliesPerSecond = 20;
  // SIM_MODEL goes out at most kModelRepliesPerSecond and, for a large
  // model, at most kModelBytesPerSecond on average, however many ask (a
  // 33-byte request returns the whole model: 20 requests/s of a 35 MB
  // model once slowed a sim to 0.017 x real time), the ruts sent with it
  // counted in. A reset's new model goes out at once.
  static constexpr int kModelRepliesPerSecond = 4;
  static constexpr double kModelBytesPerSecond = 1024.0 * 1024.0;

  // A line every kProgressEvery of wall time while running (sim time,
  // real-time factor, state) to `out`, e.g. std::cout when it is a
  // terminal; nullptr (the default) prints nothing.
  void SetProgressOutput(std::ostream* out) { progress_ = out; }
  static constexpr std::chrono::seconds kProgressEvery{5};
  // One line on how the run went, for its end: steps, sim and wall time,
  // overall real-time factor, step cost, commands, bad messages, warnings.
  std::string Summary() const;

  bool quit_requested() const { return quit_; }
  bool paused() const { return paused_; }
  double speed() const { return speed_; }
  int64_t bad_messages() const { return bad_messages_; }
  const BadMessageCounter& bad_message_counter() const { return bad_message_counter_; }
  // Times the input budget ran out with messages still waiting.
  int64_t input_deferrals() const { return input_deferrals_; }

 private:
  void OnCommand(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnControl(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnModelRequest(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnStateRequest(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnSync(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  // Checks a command with the simulation; a refusal is reported and
  // answered (rate-limited).
  void SubmitCommand(const command_t& command);
  // Lock-step: true while a synchronous controller due at the current
  // step has not answered (input is handled meanwhile); releases the ones
  // silent past lockStepTimeout. Once all answered, submits their
  // commands for the next step and returns false.
  bool WaitingForControllers();
  // Waits for the next step's deadline at speed_ (> 0), handling input;
  // false when a control or a lock-step answer woke it first.
  bool WaitForDeadline();
  void PublishReplies();
  void PublishRutChanges();
  void PublishRutParts();  // the next part of a snapshot, when due
  void StampRuts(soil_ruts_t* message) const;  // utime, simulation id, step
  // What is due besides the steps: state replies, the model (on request
  // and every modelPeriod), the status (on change and every statusPeriod).
  void PublishDue(Clock::time_point* next_model, Clock::time_point* next_status,
                  Clock::duration model_period, Clock::duration status_period);
  // Refusal replies (commands, sync marks) share kRefusalRepliesPerSecond.
  bool MayAnswerRefusal();
  // Answers pending state requests, at most kStateRepliesPerSecond.
  void ReplyState();
  // Decodes through the shared total decoder; a refusal is counted and
  // reported.
  template <class T>
  bool DecodeInput(const lcm::ReceiveBuffer* buffer, const std::string& channel, T* out);
  // A message that decoded but is refused (out of range, unknown action).
  void ReportBadMessage(const std::string& channel, const std::string& what);
  void ReportBadMessageText(const std::string& description, bool print);
  void ReportInputDeferrals();
  void PublishPending();
  void CollectWarnings();
  // Another simulation heard on the bus: said at once, as an error.
  void ReportOtherSimulations();
  // Queues `message` for the sending thread (bus_sender.h).
  template <class T>
  void Publish(const char* channel, const T& message);
  // How the sending thread's sends went: a failed send is reported
  // (channel and cause) on stderr and in SIM_STATUS, and so is the first
  // send that works again.
  void ReportSendOutcomes();
  // Reports on stderr and in the next SIM_STATUS.
  void Warn(int8_t severity, const std::string& source, const std::string& message);
  void Record(warning_t warning);  // on stderr and in the statuses

  Simulation* sim_;
  lcm::LCM* lcm_;
  int stop_fd_;
  BusSigning* signing_;
  BusSender bus_sender_;  // every message goes out through it, in order
  state_t state_;         // each step's SIM_STATE, filled in place
  std::string host_;
  std::string sender_;  // "simpartner-sim@host:pid", in SIM_MODEL
  PeerWatch peers_;
  static constexpr std::chrono::seconds kOtherSimulationReportPeriod{10};
  OtherSimulation last_other_;            // the newest id heard
  uint64_t others_unreported_ = 0;        // ids heard since the last report
  bool others_reported_ = false;
  Clock::time_point last_other_report_{};  // the epoch: the first is said at once
  bool quit_ = false;
  bool paused_ = false;
  LockStep lock_step_;
  int64_t wait_tick_ = -1;                 // the tick being waited at, -1: none
  Clock::time_point wait_start_{};
  std::deque<soil_ruts_t> rut_parts_;  // of a snapshot, still to send
  Clock::time_point next_rut_part_{};
  bool model_requested_ = false;  // asked for (SIM_MODEL_REQUEST): within the rate
  bool model_changed_ = false;    // a reset: at once
  Clock::time_point next_model_allowed_{};
  bool state_requested_ = false;
  Clock::time_point last_state_reply_{};
  bool status_changed_ = true;
  int64_t steps_to_run_ = 0;     // >0: single-stepping while paused
  double speed_ = 1.0;           // <= 0: as fast as possible
  int64_t commands_accepted_ = 0;
  int64_t commands_rejected_ = 0;
  int64_t bad_messages_ = 0;
  BadMessageCounter bad_message_counter_;
  int64_t input_deferrals_ = 0;
  std::ostream* progress_ = nullptr;
  Clock::time_point last_progress_{};
  Clock::time_point run_start_{};
  Clock::duration total_compute_time_{};
  int64_t steps_taken_ = 0;        // over the whole run, resets included
  int64_t warnings_total_ = 0;
  int64_t failed_sends_ = 0;
  int64_t failed_sends_in_outage_ = 0;  // since the last send that went out
  std::string first_failed_channel_, first_send_error_;
  Clock::time_point last_send_failure_report_{};
  int64_t reported_deferrals_ = 0;
  Clock::time_point refusal_window_start_{};
  int refusal_replies_in_window_ = 0;
  int64_t refusal_replies_withheld_ = 0;
  bool wake_ = false;            // a control arrived: stop waiting for the deadline
  std::deque<warning_t> recent_warnings_;
  std::optional<warning_t> fault_warning_;  // what faulted the run (Record)
  // Pacing and figures.
  Clock::time_point next_deadline_;
  bool schedule_anchored_ = false;
  Clock::time_point last_status_time_;
  int64_t last_status_step_ = 0;
  double real_time_factor_ = 0.0;
  double step_cost_ = 0.0;
  Clock::duration compute_time_{};
  int64_t compute_steps_ = 0;
};

// Prints the encoded sizes of SIM_MODEL and SIM_STATE, and a warning for
// one above kSafeMessageBytes: LCM splits it into fragments that a
// receiver whose socket buffer is the kernel's default (about 208 KiB)
// loses whole and silently.
inline constexpr size_t kSafeMessageBytes = 200 * 1024;
// The largest SIM_MODEL or SIM_STATE a sim publishes at all: every
// SimPartner receiver asks for a 4 MiB socket buffer (recv_buf_size=4194304,
// bus_url.h), and a message whose fragments do not fit is lost whole.
inline constexpr size_t kMaxMessageBytes = 4u << 20;
// The encoded sizes of a simulation's SIM_MODEL and SIM_STATE, measured
// once at start for both uses below.
struct MessageSizes {
  size_t model = 0;  // [bytes]
  size_t state = 0;  // [bytes]
};
MessageSizes MeasureMessages(const Simulation& sim);
// "" or, for a SIM_MODEL or SIM_STATE larger than kMaxMessageBytes, why the
// sim cannot serve it (the sizes named).
std::string MessagesTooLarge(const MessageSizes& sizes);
void ReportMessageSizes(const MessageSizes& sizes, std::ostream& out);


}  // namespace simpartner::sim
