// The viewer (and simpartner-camera) on the LCM bus: decodes SIM_MODEL, SIM_STATE, SIM_STATUS,
// SIM_SENSOR and SIM_SOIL_RUTS into a Scene, asks for the model (SIM_MODEL_REQUEST) when it
// has none or sees another simulation, and sends SIM_CONTROL and scanner
// read requests. Drain() handles everything that has arrived without
// blocking, so the scene always holds the newest state and no backlog
// builds up however fast the sim publishes.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "simpartner/bus_decode.h"
#include "simpartner/bus_signing.h"
#include "simpartner/viewer/scene.h"

namespace simpartner::viewer {

class ViewerBus {
 public:
  using Clock = std::chrono::steady_clock;
  // Problems go to `report` (stderr in the program), each kind described
  // the first time and then every 1000th time, so a flood stays readable;
  // messages refused for their signature at most once a second
  // (bus_decode.h, kSignatureReportPeriod).
  using Reporter = std::function<void(const std::string&)>;

  // Called with each state the scene accepted, while it is the scene's
  // newest (simpartner-camera renders the due ones from it).
  using StateListener = std::function<void(const state_t&)>;

  // lcm must be good(); lcm, scene and signing (null: an unsigned bus,
  // bus_signing.h) outlive the bus. `program` names the sender
  // ("viewer@host:pid").
  ViewerBus(lcm::LCM* lcm, const std::string& url, Scene* scene, Reporter report,
            BusSigning* signing = nullptr, const std::string& program = "viewer");
  ViewerBus(const ViewerBus&) = delete;
  ViewerBus& operator=(const ViewerBus&) = delete;

  // Handles every message that has arrived, then waits for more until
  // `until` (pass Clock::now() to only drain). Returns messages handled.
  int Drain(Clock::time_point until);
  // Asks for SIM_MODEL now if the scene wants one and the last request is
  // older than half a second.
  void RequestModelIfNeeded();

  // SIM_CONTROL actions (control_t::ACTION_*).
  void SendControl(int8_t action, int64_t steps = 0, double speed = 0);
  // Asks every scanner of the model for a reading (command_t::ACTION_READ).
  void RequestScans();

  void SetStateListener(StateListener listener) { state_listener_ = std::move(listener); }

  const std::string& url() const { return url_; }
  const std::string& sender() const { return sender_; }
  int64_t model_requests() const { return model_requests_; }

 private:
  void OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnStatus(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnSensor(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnSoilRuts(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void Note(const Verdict& verdict);
  // Opens (bus_signing.h) and decodes the whole buffer; false when it is
  // refused, which is counted in the scene and reported.
  template <class T>
  bool Decode(const lcm::ReceiveBuffer* buffer, const std::string& channel, T* out);

  lcm::LCM& lcm_;
  std::string url_;
  Scene* scene_;
  Reporter report_;
  StateListener state_listener_;
  std::string sender_;
  BusSigning* signing_;
  BadMessageCounter signature_refusals_;
  bool want_model_ = true;
  Clock::time_point last_request_{};
  int64_t model_requests_ = 0;
  int64_t request_id_ = 0;
};


}  // namespace simpartner::viewer
