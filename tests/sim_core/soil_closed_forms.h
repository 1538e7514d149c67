// The closed forms of wheel-soil mechanics the sim's soil tests compare
// with (validate/include/simpartner/validate/soil_closed_forms.h, written
// apart from the sim's code; the validation's soil experiments use them
// too), and the tests' soils.
#pragma once

#include "simpartner/model/model.h"
#include "simpartner/validate/soil_closed_forms.h"

namespace simpartner::sim::testing {

using validate::Bekker;
using validate::RollingArc;
using validate::RollingSinkage;
using validate::RollingStresses;
using validate::RollingWheel;
using validate::RollingWheelForces;
using validate::Simpson;
using validate::StandingLoad;

// Wong (2008), Table 2.3 (n, k_c, k_phi, c, phi), with K = 0.025 m and an
// unloading stiffness of 20,000 kPa/m of these tests' choosing.
inline model::SoilParameters WongEntry(double n, double kc, double kphi, double c, double phi) {
  model::SoilParameters p;
  p.n = n;
  p.k_c = kc;
  p.k_phi = kphi;
  p.cohesion = c;
  p.friction_angle = phi;
  p.shear_modulus = 0.025;
  p.unloading_stiffness = 20000;
  return p;
}

}  // namespace simpartner::sim::testing
