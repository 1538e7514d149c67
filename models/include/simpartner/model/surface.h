// The contact properties of a surface, resolved from its material and the
// parameters, and the rule that combines two surfaces into one contact.
// Pure arithmetic on the model, shared by the sim (which turns it into
// ODE's contact) and the MJCF exporter (which writes MuJoCo's).
#pragma once

#include "simpartner/model/model.h"
#include "simpartner/parameters.h"

namespace simpartner::model {

// Contact properties of one geom, resolved from its material name.
struct SurfaceProperties {
  double mu = 1.0;                 // along the first friction direction
  double mu2 = 1.0;                // across it (= mu when isotropic)
  FrictionDirection friction_direction = FrictionDirection::kSlip;
  double bounce = 0.0, bounce_velocity = 0.1;
  // ERP and CFM of the whole contact for the step size in use; for a
  // material with stiffness, computed from stiffness and damping.
  double soft_erp = 0.2, soft_cfm = 1e-5;
  // [N/m], [N s/m] of the whole contact; 0 when the softness is per step.
  double stiffness = 0.0, damping = 0.0;
  double rolling_friction = 0.0;

  bool HasStiffness() const { return stiffness > 0.0; }
};

// A material's contact properties for params.stepsize; a geom without one
// (nullptr) takes the contact defaults of the parameters. With stiffness k
// and damping c: ERP = h k / (h k + c), CFM = 1 / (h k + c) (ODE's manual,
// "Soft constraint and constraint force mixing").
SurfaceProperties ResolveSurface(const Material* material, const Parameters& params);
// The contact between two surfaces, as the sim makes it (docs/contacts.md):
// mu, mu2 and rolling resistance each the smaller, bounce the larger;
// softness: between two per-step materials the smaller ERP and the larger
// CFM, otherwise all of the softer material's (smaller ERP / CFM, i.e.
// smaller stiffness at this step size); the first friction direction
// "rolling" when exactly one side has it, else "slip".
SurfaceProperties CombineSurfaces(const SurfaceProperties& a, const SurfaceProperties& b);

}  // namespace simpartner::model
