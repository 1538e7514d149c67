// Closed forms of wheel-soil mechanics for the soil tests, written apart
// from the sim's code (sim_core/soil_mechanics.h): Simpson's rule on
// 20,000 intervals of Bekker's stresses along a circular rim.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>

#include "simpartner/model/model.h"

namespace simpartner::sim::testing {

inline double Simpson(const std::function<double(double)>& f, double a, double b,
                      int intervals = 20000) {
  const double h = (b - a) / intervals;
  double sum = f(a) + f(b);
  for (int k = 1; k < intervals; ++k) sum += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
  return sum * h / 3.0;
}

// Bekker's pressure [Pa] at sinkage z [m] under width b [m], from the
// table's units (kN/m^(n+1), kN/m^(n+2)).
inline double Bekker(const model::SoilParameters& p, double b, double z) {
  return z > 0 ? (p.k_c * 1e3 / b + p.k_phi * 1e3) * std::pow(z, p.n) : 0.0;
}

// The load [N] a standing wheel (radius r, width b) carries at sinkage z
// in untouched soil: b r times the integral of p cos(theta) over the arc.
inline double StandingLoad(const model::SoilParameters& p, double r, double b, double z) {
  const double half = std::acos(1.0 - z / r);
  return b * r * Simpson([&](double t) { return Bekker(p, b, z - r * (1 - std::cos(t))) * std::cos(t); },
                         -half, half);
}

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
