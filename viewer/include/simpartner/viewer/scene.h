// What the viewer knows about the running simulation, learned only from the
// bus: the model of SIM_MODEL, the newest acceptable SIM_STATE, the last
// SIM_STATUS, the latest scanner reading per sensor and the soil's ruts
// (SIM_SOIL_RUTS). No GL and no LCM
// here, so the bookkeeping is unit tested on plain messages.
//
// A message that does not fit (a state of another simulation, with the
// wrong number of bodies or joints, a non-finite or non-unit pose) is
// ignored, counted by kind and described once per kind with the channel,
// field and value; the scene keeps showing the last good state.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "simpartner/message_checks.h"
#include "simpartner/model_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "simpartner/simulation_follower.h"
#include "simpartner/state_t.hpp"
#include "simpartner/status_t.hpp"
#include "simpartner/viewer/soil_ruts.h"

namespace simpartner::viewer {

// Why a message was ignored.
enum class Rejection {
  kUndecodable,        // bytes that do not decode as the channel's type
  kOtherSimulation,    // simulation_id differs from the model's
  kBodyCount,          // state_t.num_bodies != model_t.num_bodies
  kJointCount,         // state_t.num_joints != model_t.num_joints
  kNonFinite,          // NaN or infinity in a pose, velocity or force
  kBadQuaternion,      // orientation far from unit length
  kBadModel,           // a SIM_MODEL the viewer cannot draw (sizes, indices)
  kBadReading,         // a SIM_SENSOR reading that does not fit its sensor
  kBadRuts,            // a SIM_SOIL_RUTS message that does not fit (soil_ruts.h)
  kBadState,           // a SIM_STATE out of range otherwise (a negative step, a wheel of no body)
};
inline constexpr int kRejectionKinds = 10;
const char* RejectionName(Rejection r);

// One ignored message, described for stderr and the HUD.
struct Problem {
  Rejection kind;
  std::string channel;
  std::string message;  // "SIM_STATE: bodies[2].position[0] = nan (body 'Arm'): ..."
};

// Result of offering a message to the scene.
struct Verdict {
  bool accepted = false;
  std::optional<Problem> problem;  // set when not accepted
  bool want_model = false;         // the model is missing or stale: ask SIM_MODEL_REQUEST
};

class Scene {
 public:
  // A model of a new simulation replaces everything (poses go back to the
  // model's initial ones until its first state); the periodic
  // re-announcement of the same simulation only refreshes sensor settings.
  Verdict OfferModel(const model_t& model);
  Verdict OfferState(state_t&& state);
  Verdict OfferStatus(const status_t& status);
  Verdict OfferSensorReading(const sensor_reading_t& reading);
  Verdict OfferSoilRuts(const soil_ruts_t& ruts);
  // Counts (and describes) a message the bus could not decode.
  void CountUndecodable(const std::string& channel, const std::string& refusal);

  bool has_model() const { return model_.has_value(); }
  const model_t& model() const { return *model_; }
  // Bumped whenever the model's geometry may have changed (a new
  // simulation), so cached meshes know to rebuild.
  int64_t model_generation() const { return model_generation_; }
  int64_t simulation_id() const { return model_ ? model_->simulation_id : 0; }

  bool has_state() const { return state_.has_value(); }
  const state_t* state() const { return state_ ? &*state_ : nullptr; }
  int64_t states_accepted() const { return states_accepted_; }
  // States that came before any model (normal for a viewer that starts
  // while a sim runs): not a problem, so not counted as rejected.
  int64_t states_before_model() const { return states_before_model_; }
  const status_t* status() const { return status_ ? &*status_ : nullptr; }

  // World pose of body i: the newest state's, or the model's initial pose.
  Eigen::Isometry3d BodyPose(int i) const;
  // Up (opposite to gravity), unit length; y when the model has none.
  Eigen::Vector3d Up() const;
  // What the camera follows: the centre of robot 0's bodies in the current
  // poses, or in a world without robots the centre of the bodies that
  // move; nullopt when there is neither.
  std::optional<Eigen::Vector3d> FollowPoint() const;
  // Centre and radius of a sphere around what the camera should frame at
  // start: robot 0, else all bodies, else the heightfield.
  std::pair<Eigen::Vector3d, double> FocusSphere() const;

  // The ruts in the soil of one ground (soil_ruts_t::GROUND_*; this
  // simulation only).
  const RutMap& ruts(int8_t ground = soil_ruts_t::GROUND_PLANE) const {
    return ruts_[ground == soil_ruts_t::GROUND_HEIGHTFIELD ? 1 : 0];
  }

  // Latest scanner reading per sensor index (this simulation only).
  const std::map<int, sensor_reading_t>& scans() const { return scans_; }

  // Changes with every message that changed what is shown (including
  // counted problems), so a viewer can skip drawing when nothing did.
  int64_t version() const { return version_; }

  // Bad-input bookkeeping.
  int64_t rejected(Rejection r) const { return rejected_[static_cast<int>(r)]; }
  int64_t rejected_total() const;
  // The most recent problems, newest last (bounded).
  const std::deque<Problem>& recent_problems() const { return recent_problems_; }
  // "3 other simulation, 2 body count" (empty when nothing was rejected).
  std::string RejectionSummary() const;

 private:
  Verdict Reject(Rejection kind, const std::string& channel, const std::string& message);

  std::optional<model_t> model_;
  ModelOutline outline_;  // of model_, what its states and readings must fit
  SimulationFollower follower_;  // which SIM_MODEL is the shown sim's
  int64_t version_ = 0;
  int64_t model_generation_ = 0;
  std::optional<state_t> state_;
  int64_t states_accepted_ = 0;
  int64_t states_before_model_ = 0;
  std::optional<status_t> status_;
  std::map<int, sensor_reading_t> scans_;
  std::array<RutMap, 2> ruts_;  // by ground
  std::array<int64_t, kRejectionKinds> rejected_{};
  std::deque<Problem> recent_problems_;
};

}  // namespace simpartner::viewer
