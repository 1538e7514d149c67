#include "contact_rules.h"

#include <cmath>

#include "simpartner/model/model.h"

namespace simpartner::sim {
namespace {

bool WithinRanges(const BodyState& s) {
  namespace limits = model::limits;
  const bool finite = s.position.allFinite() && s.orientation.allFinite() &&
                      s.linear_velocity.allFinite() && s.angular_velocity.allFinite();
  return finite && s.position.cwiseAbs().maxCoeff() <= limits::kMaxCoordinate &&
         s.linear_velocity.norm() <= limits::kMaxLinearSpeed &&
         s.angular_velocity.norm() <= limits::kMaxAngularSpeed;
}

bool MassWithinRange(double mass) {
  return mass >= model::limits::kMinMass && mass <= model::limits::kMaxMass;
}

}  // namespace

std::optional<Eigen::Vector3d> SlipDirection(const Eigen::Vector3d& slip) {
  const double speed = slip.norm();
  if (!(speed > kSlipDirectionSpeed)) return std::nullopt;
  return Eigen::Vector3d(slip / speed);
}

std::optional<Eigen::Vector3d> RollingDirection(
    const model::SurfaceProperties& combined, const Eigen::Vector3d& normal,
    const std::optional<Eigen::Vector3d>& spin_axis1,
    const std::optional<Eigen::Vector3d>& spin_axis2) {
  if (combined.friction_direction != model::FrictionDirection::kRolling) return std::nullopt;
  if (spin_axis1.has_value() == spin_axis2.has_value()) return std::nullopt;
  const Eigen::Vector3d rolling = normal.cross(spin_axis1 ? *spin_axis1 : *spin_axis2);
  const double sine = rolling.norm();
  if (!(sine > kMinRollingSine)) return std::nullopt;  // a wheel lying flat rolls nowhere
  return Eigen::Vector3d(rolling / sine);
}

std::vector<std::string> SuspectBodies(const model::FlatModel& model,
                                       const std::vector<BodyState>& moving) {
  std::vector<std::string> names;
  for (const BodyState& state : moving) {
    const double mass = model.bodies[static_cast<size_t>(state.body)].source->mass;
    if (!WithinRanges(state) || !MassWithinRange(mass))
      names.push_back(model::QualifiedBodyName(model, state.body));
  }
  return names;
}

}  // namespace simpartner::sim
