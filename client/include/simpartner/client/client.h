// Control code's connection to the sim over LCM.
//
// Threading: a Client owns one receive thread that handles the bus and
// keeps the newest state, status, sensor readings, camera images (once
// asked for), the replies addressed to this client and the newest model. Every public method may be called from
// any thread (teleop's UI loop, a sequencer's main loop); they only lock a
// mutex briefly and publish, or wait on a condition variable fed by the
// receive thread. Callbacks (OnState, OnReading) run on the receive thread:
// keep them short, and do not call waiting methods, OnState or OnReading
// from them.
//
// Input: every message is decoded through DecodeFromBus; messages that
// decode but do not fit the model (a state with other body counts, a
// reading of a sensor the model lacks, a model whose indices contradict
// it, an image that does not fit its camera: image_store.h) are counted as
// bad too (BadMessageSummary) and ignored.
//
// Camera images (SIM_IMAGE, from simpartner-camera) are ~1 MB each at
// 30 Hz a camera, so the client subscribes to SIM_IMAGE only at the first
// call of LatestImage or WaitForImage: a client that never asks for an
// image never receives or decodes one.
//
// Restarts: when a SIM_MODEL with a new simulation id arrives (a sim sends
// it when it starts or resets, and every modelPeriod),
// every call that depends on the model (Send, Command, Wait*) throws
// SimRestarted until Relearn() takes the new model; then the client goes
// on. Reset() does this by itself. Run control (Pause, Resume, ...) and the
// Latest* getters never throw it.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "simpartner/bus_decode.h"
#include "simpartner/message_checks.h"
#include "simpartner/client/catalog.h"
#include "simpartner/client/command.h"
#include "simpartner/client/errors.h"
#include "simpartner/client/image_store.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_t.hpp"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/sync_reply_t.hpp"
#include "simpartner/sync_t.hpp"
#include "simpartner/simulation_follower.h"

namespace lcm {
class LCM;
class ReceiveBuffer;
}

namespace simpartner::client {

class LockStep;

// The message types, so that `using namespace simpartner::client;` is all
// a controller needs.
using simpartner::body_state_t;
using simpartner::command_reply_t;
using simpartner::command_t;
using simpartner::model_t;
using simpartner::sensor_reading_t;
using simpartner::state_t;
using simpartner::status_t;

inline constexpr const char* kDefaultUrl = "udpm://239.255.76.67:7667?ttl=0";

struct ClientOptions {
  std::string url = kDefaultUrl;
  // Program name in the sender field: "<program>@<host>:<pid>".
  std::string program = "client";
  // How long the constructor waits for SIM_MODEL [s] (NoSim after it).
  double model_timeout = 3.0;
  // Default wait for a command's reply [s] (Timeout after it).
  double reply_timeout = 2.0;
  // false: do not wait for the model in the constructor (status, pause,
  // quit work without one); catalog() is empty until Relearn().
  bool learn_model = true;
  // Commands and run control carry the id of the simulation they were
  // built for, and a sim refuses one meant for another simulation (two
  // systems on one bus). true: send 0, which any sim accepts.
  bool any_simulation = false;
  // The simulation this client is attached to: only its models, states
  // and statuses are taken (and those of its resets), and its id goes
  // with every command and control. 0: the first simulation heard (a
  // SIM_MODEL, SIM_STATUS or SIM_STATE). A followed simulation silent for
  // 2.5 s is given up for a newer one (simulation_follower.h).
  int64_t simulation_id = 0;
};

class Client {
 public:
  // Connects and (unless options.learn_model is false) learns the model.
  // Throws ClientError when the URL is bad, NoSim when no model comes.
  explicit Client(ClientOptions options = {});
  ~Client();
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  const std::string& url() const { return options_.url; }
  const std::string& sender() const { return sender_; }

  // The model learned last (replaced only by Relearn/Reset).
  std::shared_ptr<const Catalog> catalog() const;
  std::shared_ptr<const model_t> model() const;
  // Shorthand for catalog()->Resolve(name_or_port); throws UnknownTarget,
  // and SimRestarted while a restart is pending.
  Target Find(const std::string& name_or_port) const;

  // Fire and forget: fills utime, request_id, sender and simulation_id (the
  // learned model's, or 0 with any_simulation), publishes, returns
  // the request id (its reply can be looked up with TakeReply). Throws
  // SimRestarted when the sim restarted since the model was learned.
  // In lock-step (a LockStep on this client) the command is not published
  // but goes with the answer to the current tick: it applies in the step
  // after it, and LockStep::Next throws Refused if the sim refused it.
  int64_t Send(command_t command);
  // Builds (BuildCommandFromText) and sends.
  int64_t Send(const std::string& target, int action, const std::string& text,
               int64_t apply_at_step = -1);
  // Sends and waits for the reply: returns it when accepted (previous /
  // previous_text hold the setting it replaced); throws Refused, Timeout
  // (timeout < 0: options.reply_timeout), SimRestarted. An accepted
  // command is answered when it is applied, so one with apply_at_step
  // ahead of the sim waits until that step. In lock-step it throws
  // ClientError: the reply comes only after the sim steps, which waits
  // for this controller; use Send.
  command_reply_t Command(command_t command, double timeout = -1);
  command_reply_t Command(const std::string& target, int action, const std::string& text,
                          int64_t apply_at_step = -1, double timeout = -1);
  // The reply to a sent request, if it has come (removed when taken).
  std::optional<command_reply_t> TakeReply(int64_t request_id);

  // Run control (SIM_CONTROL), fire and forget. It carries the id of the
  // simulation the client is attached to: the newest one followed (so it
  // reaches a restarted sim before Relearn), even without a model; 0 only
  // before any sim was heard, or with any_simulation.
  void Pause();
  void Resume();
  void Step(int64_t steps);
  void SetSpeed(double real_time_factor);  // <= 0: as fast as possible
  void Quit();
  // Resets the sim and learns its new model (the sim gives a reset a new
  // simulation id). Throws NoSim when the new model does not come.
  std::shared_ptr<const Catalog> Reset(double timeout = 3.0);

  // Newest messages, or nothing before the first one.
  std::optional<state_t> LatestState() const;
  std::optional<status_t> LatestStatus() const;
  // What the client heard that may explain a missing answer: a signed bus
  // and no key, an unsigned bus and a key, or another key
  // (SigningMismatch). "" when nothing suggests it. Timeouts and NoSim
  // carry it.
  std::string SigningHint() const;
  std::optional<sensor_reading_t> LatestReading(const std::string& sensor) const;
  // Waits for a reading of `sensor` (name as in the model) from a step
  // after `after_step`; throws Timeout, SimRestarted.
  sensor_reading_t WaitForReading(const std::string& sensor, int64_t after_step, double timeout);
  // The newest image of a camera sensor (name as in the model): colour
  // (image_t.FORMAT_RGB8) or depth (FORMAT_DEPTH_F32 or _U16, as the
  // camera declares). Nothing before the first; the first call subscribes
  // to SIM_IMAGE, so it returns nothing. Throws UnknownTarget when
  // `camera` is not a camera.
  std::optional<image_t> LatestImage(const std::string& camera,
                                     ImageKind kind = ImageKind::kColour);
  // Waits for an image of `camera` from a step after `after_step` (e.g.
  // the step of a state, or the step a command was applied at); throws
  // Timeout, SimRestarted, UnknownTarget.
  image_t WaitForImage(const std::string& camera, int64_t after_step, double timeout,
                       ImageKind kind = ImageKind::kColour);
  // Waits for a SIM_STATE with sim_time >= t - half a step; returns it.
  // Throws Timeout, SimRestarted.
  state_t WaitUntilSimTime(double sim_time, double timeout);
  // Waits for a SIM_STATUS newer than the call (e.g. after a Pause).
  status_t WaitForStatus(double timeout);
  // The sim's state now, running or paused: asks with SIM_STATE_REQUEST
  // and waits for the answer on SIM_STATE_REPLY (asking again every
  // 0.25 s). A paused sim sends no SIM_STATE, so this is how it is
  // inspected. Throws Timeout, SimRestarted. The answer also becomes
  // LatestState() but is not passed to OnState (it repeats a step).
  state_t RequestState(double timeout);

  // Called on the receive thread for every state / reading of the current
  // simulation. One callback each; an empty function removes it.
  void OnState(std::function<void(const state_t&)> callback);
  void OnReading(std::function<void(const sensor_reading_t&)> callback);

  // Seconds since the last SIM_STATE (of any simulation: a restarted sim is
  // there before it is followed) or SIM_STATUS; infinity before the
  // first. A running sim sends states every stateEvery steps; a paused one
  // only its status, every statusPeriod (1 s): tell a paused sim from a
  // silent one with LatestStatus()->run_state.
  double SecondsSinceHeard() const;
  // The restart noticed and not yet followed, if any (does not throw).
  std::optional<SimRestarted> PendingRestart() const;
  // Learns the model of the sim now on the bus (asks with
  // SIM_MODEL_REQUEST, waits up to `timeout`), clears a pending restart.
  // Throws NoSim.
  std::shared_ptr<const Catalog> Relearn(double timeout = 3.0);

  // Bad messages received, "SIM_STATE 2, ..." or "".
  std::string BadMessageSummary() const;

  // The lock-step tick whose answer Send adds to, or -1 when not in
  // lock-step.
  int64_t LockStepTick() const;

 private:
  using Clock = std::chrono::steady_clock;
  void ReceiveLoop();
  void OnMessageBuffer(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnMessage(const void* data, size_t size, const std::string& channel);
  // Waits for a SIM_MODEL accepted by `accept`, adopts it; NoSim after timeout.
  std::shared_ptr<const Catalog> LearnModel(double timeout,
                                            const std::function<bool(const model_t&)>& accept);
  void Publish(const std::string& channel, const void* data, int size);
  void SendControl(int action, int64_t steps, double speed);
  void ThrowIfRestarted() const;  // requires mutex_ held
  void RequestModel();
  // For LockStep: the bus side of the lock-step protocol.
  friend class LockStep;
  void PublishSync(sync_t message);
  // The oldest SIM_SYNC_REPLY for this sender and `controller`, taken.
  std::optional<sync_reply_t> TakeSyncReply(const std::string& controller);
  // Waits up to `wait` for a state (SIM_STATE or SIM_STATE_REPLY) of step
  // >= step, or a reply on SIM_SYNC_REPLY; the state when there is one.
  // Throws SimRestarted.
  std::optional<state_t> WaitForStepOrSyncReply(int64_t step, Clock::duration wait);
  void EnterLockStep(const std::string& controller, int64_t tick);
  // The commands Send queued for the current tick, taken; then the tick.
  std::vector<command_t> TakeLockStepCommands(int64_t next_tick);
  void LeaveLockStep();
  void PublishStateRequest();
  // Takes a decoded SIM_STATE or SIM_STATE_REPLY; false when it is not a
  // state of the learned simulation. Requires mutex_ held.
  bool AcceptState(const state_t& state, const std::string& channel);
  void NoteSimulation(int64_t simulation_id);  // requires mutex_ held
  // A SIM_STATE or SIM_STATUS of `simulation_id` came: attaches to it when
  // it is the first sim heard; true when it is the attached one (or was,
  // before a reset). Requires
  // mutex_ held.
  bool HeardFromAttached(int64_t simulation_id);
  // The camera sensor `camera` names (its index); subscribes to SIM_IMAGE
  // on the first call. Throws UnknownTarget, NoSim.
  int CameraIndex(const std::string& camera);

  ClientOptions options_;
  std::string sender_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::mutex publish_mutex_;  // also keeps signed timestamps in send order

  mutable std::mutex mutex_;
  std::condition_variable changed_;
  // States, sync replies and restarts only: a lock-step controller waiting
  // for its tick is not woken by each command reply and status.
  std::condition_variable step_changed_;
  std::shared_ptr<const Catalog> catalog_;
  std::shared_ptr<const model_t> model_;         // learned
  ModelOutline outline_;                         // of model_: what states and readings fit
  std::shared_ptr<const model_t> newest_model_;  // last seen on the bus
  std::shared_ptr<const Catalog> newest_catalog_;  // built from it (it is valid)
  std::optional<state_t> state_;
  std::optional<status_t> status_;
  uint64_t status_count_ = 0;
  uint64_t state_reply_count_ = 0;
  std::optional<state_t> state_reply_;
  uint64_t model_count_ = 0;
  std::map<int, sensor_reading_t> readings_;  // by sensor index
  ImageStore images_;             // of the learned model (guarded by mutex_)
  bool images_subscribed_ = false;  // SIM_IMAGE (set under mutex_)
  std::map<int64_t, command_reply_t> replies_;
  std::optional<SimRestarted> restart_;
  int64_t latest_simulation_id_ = 0;
  SimulationFollower follower_;  // which SIM_MODEL is our sim's (guarded by mutex_)
  std::optional<BusSigning> signing_;  // SIMPARTNER_BUS_KEY: sign and check (thread-safe)
  SigningMismatch signing_mismatch_;   // guarded by mutex_
  std::optional<Clock::time_point> last_heard_;
  // Held while a callback runs, so that once OnState/OnReading returns the
  // old callback is not running any more.
  std::mutex callback_mutex_;
  std::function<void(const state_t&)> on_state_;
  std::function<void(const sensor_reading_t&)> on_reading_;
  std::atomic<bool> catalog_known_{false};
  BadMessageCounter bad_messages_;
  int64_t next_request_id_ = 1;
  // Lock-step (LockStep): the controller ("" when not in lock-step), its
  // current tick and the commands queued for its answer.
  std::string lock_step_controller_;
  int64_t lock_step_tick_ = -1;
  std::vector<command_t> lock_step_queue_;
  std::deque<sync_reply_t> sync_replies_;  // for this sender, oldest first (bounded)
  std::atomic<bool> stop_{false};
  std::thread receiver_;
};

}  // namespace simpartner::client
