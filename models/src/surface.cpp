#include "simpartner/model/surface.h"

#include <algorithm>

namespace simpartner::model {

SurfaceProperties ResolveSurface(const Material* material, const Parameters& params) {
  SurfaceProperties s;
  if (material == nullptr) {
    s.mu = params.contactMu;
    s.mu2 = params.contactMu;
    s.bounce = params.contactBounce;
    s.bounce_velocity = params.contactBounceVelocity;
    s.soft_erp = params.contactSoftERP;
    s.soft_cfm = params.contactSoftCFM;
    s.rolling_friction = params.rollingFriction;
  } else {
    s.mu = material->mu;
    s.mu2 = material->Mu2();
    s.friction_direction = material->friction_direction;
    s.bounce = material->bounce;
    s.bounce_velocity = material->bounce_velocity;
    s.rolling_friction = material->rolling_friction;
    if (material->HasStiffness()) {
      // ODE's contact is an implicit spring-damper: these give stiffness k
      // and damping c whatever the step h.
      const double h = params.stepsize;
      const double k = *material->stiffness;
      const double c = material->damping.value_or(0.0);
      s.stiffness = k;
      s.damping = c;
      s.soft_erp = h * k / (h * k + c);
      s.soft_cfm = 1.0 / (h * k + c);
    } else {
      s.soft_erp = material->soft_erp;
      s.soft_cfm = material->soft_cfm;
    }
  }
  return s;
}

SurfaceProperties CombineSurfaces(const SurfaceProperties& a, const SurfaceProperties& b) {
  SurfaceProperties s;
  s.mu = std::min(a.mu, b.mu);
  s.mu2 = std::min(a.mu2, b.mu2);
  // Either side may ask for the rolling direction: a tyre's material, or a
  // ground's for every wheel on it. Which wheel's axis gives it is decided
  // per contact (FrictionDirection1): the one geom of the pair that spins.
  const bool a_rolls = a.friction_direction == FrictionDirection::kRolling;
  const bool b_rolls = b.friction_direction == FrictionDirection::kRolling;
  s.friction_direction =
      a_rolls || b_rolls ? FrictionDirection::kRolling : FrictionDirection::kSlip;
  s.rolling_friction = std::min(a.rolling_friction, b.rolling_friction);
  s.bounce = std::max(a.bounce, b.bounce);
  s.bounce_velocity = std::max(a.bounce_velocity, b.bounce_velocity);
  if (!a.HasStiffness() && !b.HasStiffness()) {
    s.soft_erp = std::min(a.soft_erp, b.soft_erp);
    s.soft_cfm = std::max(a.soft_cfm, b.soft_cfm);
  } else {
    // The softer decides whole, so that a physical tyre on a per-step
    // ground keeps its own k and c: k = ERP / (h CFM), compared at the same
    // h without dividing (a CFM may be 0).
    const SurfaceProperties& softer = a.soft_erp * b.soft_cfm <= b.soft_erp * a.soft_cfm ? a : b;
    s.soft_erp = softer.soft_erp;
    s.soft_cfm = softer.soft_cfm;
    s.stiffness = softer.stiffness;
    s.damping = softer.damping;
  }
  return s;
}

}  // namespace simpartner::model
