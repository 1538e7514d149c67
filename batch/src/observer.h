// What a batch run's bus shows, taken as it comes: the model (for the
// bodies' indices), every SIM_STATE hashed in step order (wall clock and
// simulation id left out: they differ from run to run), and the figures
// of the batch file.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/batch/batch_file.h"
#include "simpartner/bus_decode.h"
#include "simpartner/model_t.hpp"
#include "simpartner/state_t.hpp"

namespace simpartner::batch {

class RunObserver {
 public:
  // Opens `url` (throws std::runtime_error when LCM cannot).
  RunObserver(const std::string& url, const std::vector<Figure>& figures);
  // Handles what arrives until nothing has for `quiet_ms`, or for
  // `budget_ms` at most (states keep coming while a sim runs).
  void Pump(int quiet_ms, int budget_ms = 100);

  int64_t states() const { return states_; }
  int64_t last_step() const { return last_step_; }
  double sim_time() const { return sim_time_; }
  // 16 hex digits; "" when a state was missed (a step skipped, or the
  // stream ended before `last_step`).
  std::string Hash(int64_t last_step) const;
  // The model's step size [s], 0 before the model.
  double step_size() const { return model_ ? model_->step_size : 0.0; }
  // In the figures' order; NaN for a body the model lacks or no state.
  std::vector<double> Figures() const;

 private:
  struct Accumulator {
    int body = -1;
    bool any = false;
    double position[3] = {0, 0, 0}, speed = 0, path = 0, peak_force = 0;
  };
  void OnModel(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void OnState(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void Accumulate(const state_t& state);

  lcm::LCM lcm_;
  std::vector<Figure> figures_;
  std::vector<Accumulator> accumulators_;
  std::optional<model_t> model_;
  BadMessageCounter refused_;
  uint64_t hash_ = 1469598103934665603ull;  // FNV-1a offset basis
  bool complete_ = true;
  int64_t states_ = 0, last_step_ = -1;
  double sim_time_ = 0;
};

}  // namespace simpartner::batch
