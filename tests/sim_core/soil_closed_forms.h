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

namespace simpartner::sim::testing {

// A rigid wheel (radius r, width b) rolling steadily at slip i, sunk z0
// below untouched soil; the track behind its lowest point was pressed to
// z0 and rebounds along the unloading line. Wong's rigid-wheel integrals:
// normal stress sigma (Bekker ahead of the lowest point, the unloading
// line behind), shear tau (Janosi-Hanamoto, with Wong and Reece's shear
// displacement j = r [(theta_f - theta) - (1 - i)(sin theta_f - sin theta)]).
struct RollingWheelForces {
  double load = 0;  // carried: b r int (sigma cos + tau sin) [N]
  double pull = 0;  // drawbar pull: b r int (tau cos - sigma sin) [N]
};

inline RollingWheelForces RollingWheel(const model::SoilParameters& p, double r, double b,
                                       double z0, double slip) {
  const double k_u = p.unloading_stiffness * 1e3, tan_phi = std::tan(p.friction_angle * M_PI / 180);
  const double front = std::acos(1.0 - z0 / r);
  const double rear = -std::acos(std::max(-1.0, 1.0 - Bekker(p, b, z0) / (k_u * r)));
  auto sigma = [&](double t) {
    const double z = z0 - r * (1.0 - std::cos(t));
    return t >= 0 ? Bekker(p, b, z) : std::max(0.0, Bekker(p, b, z0) - k_u * (z0 - z));
  };
  auto tau = [&](double t) {
    const double j = r * ((front - t) - (1 - slip) * (std::sin(front) - std::sin(t)));
    return (p.cohesion * 1e3 + sigma(t) * tan_phi) * (1 - std::exp(-j / p.shear_modulus));
  };
  RollingWheelForces out;
  out.load = b * r * Simpson([&](double t) { return sigma(t) * std::cos(t) + tau(t) * std::sin(t); },
                             rear, front);
  out.pull = b * r * Simpson([&](double t) { return tau(t) * std::cos(t) - sigma(t) * std::sin(t); },
                             rear, front);
  return out;
}

// The sinkage at which that wheel carries `load` (bisection).
inline double RollingSinkage(const model::SoilParameters& p, double r, double b, double slip,
                             double load) {
  double lo = 0.0, hi = r;
  for (int k = 0; k < 50; ++k)
    (RollingWheel(p, r, b, 0.5 * (lo + hi), slip).load < load ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

}  // namespace simpartner::sim::testing
