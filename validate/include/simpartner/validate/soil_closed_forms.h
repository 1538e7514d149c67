// Closed forms of rigid-wheel mechanics on soil (Bekker, Janosi-Hanamoto,
// Wong-Reece; Wong, Theory of Ground Vehicles, 4th ed., 2008, ch. 2 and 4),
// written apart from the sim's code (sim_core/soil_mechanics.h): Simpson's
// rule along a circular rim, bisection for a sinkage. The validation's
// soil experiments and the sim's soil tests take their targets from here.
// Figures come in the files' units (model::SoilParameters); results in N,
// m and Pa.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>

#include "simpartner/model/model.h"

namespace simpartner::validate {

inline constexpr int kSimpsonIntervals = 20000;

inline double Simpson(const std::function<double(double)>& f, double a, double b,
                      int intervals = kSimpsonIntervals) {
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
inline double StandingLoad(const model::SoilParameters& p, double r, double b, double z,
                           int intervals = kSimpsonIntervals) {
  const double half = std::acos(1.0 - z / r);
  return b * r *
         Simpson([&](double t) { return Bekker(p, b, z - r * (1 - std::cos(t))) * std::cos(t); },
                 -half, half, intervals);
}

// The sinkage [m] at which a standing wheel carries `load` [N] (bisection).
inline double StandingSinkage(const model::SoilParameters& p, double r, double b, double load,
                              int intervals = kSimpsonIntervals) {
  double lo = 0.0, hi = r;
  for (int k = 0; k < 50; ++k)
    (StandingLoad(p, r, b, 0.5 * (lo + hi), intervals) < load ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// A rigid wheel (radius r, width b) rolling steadily at slip i, its lowest
// point z0 below the untouched surface, in a rut `rut` deep that an earlier
// pass pressed (0: untouched soil; the rut rebounded along the unloading
// line). Wong's rigid-wheel integrals over the arc where the soil pushes:
// normal stress sigma (Bekker where the rim presses deeper than the soil
// ever was, the unloading line p(z_max) - k_u (z_max - z) where it was
// pressed deeper before: the rut, and behind the lowest point), shear tau
// (Janosi-Hanamoto, with Wong and Reece's shear displacement
// j = r [(theta_f - theta) - (1 - i)(sin theta_f - sin theta)] from where
// the soil starts to push, theta_f).
struct RollingWheelForces {
  double load = 0;        // carried: b r int (sigma cos + tau sin) [N]
  double pull = 0;        // drawbar pull: b r int (tau cos - sigma sin) [N]
  double compaction = 0;  // the normal stresses' resistance: b r int sigma sin [N]
};

// The stresses along that wheel's loaded arc, theta from `rear` to `front`.
struct RollingArc {
  double front = 0, rear = 0;
  std::function<double(double)> sigma, tau;
};

// The unloading line's slope [Pa/m] below a deepest sinkage z_max under
// a plate of width b: Wong's k_u = k_0 + A_u z_max, and never shallower
// than Bekker's curve's steepest chord below z_max, max(1, n) p(z_max) /
// z_max, so that unloading and loading never cross.
inline double UnloadingSlope(const model::SoilParameters& p, double b, double z_max) {
  const double wong = (p.unloading_stiffness + p.unloading_growth * z_max) * 1e3;
  return z_max > 0 ? std::max(wong, std::max(1.0, p.n) * Bekker(p, b, z_max) / z_max) : wong;
}

inline RollingArc RollingStresses(const model::SoilParameters& p, double r, double b, double z0,
                                  double slip, double rut) {
  const double tan_phi = std::tan(p.friction_angle * M_PI / 180);
  // Where the soil starts to push ahead (the rut's rebounded floor) and
  // how deep it was ever pressed behind the lowest point.
  const double rut_floor =
      rut > 0 ? std::max(0.0, rut - Bekker(p, b, rut) / UnloadingSlope(p, b, rut)) : 0.0;
  const double deepest = std::max(z0, rut);
  RollingArc arc;
  arc.front = std::acos(std::clamp(1.0 - (z0 - rut_floor) / r, -1.0, 1.0));
  arc.rear = -std::acos(std::clamp(
      1.0 - (z0 - (deepest - Bekker(p, b, deepest) / UnloadingSlope(p, b, deepest))) / r, -1.0,
      1.0));
  auto unloaded = [&p, b](double z, double z_max) {
    return std::max(0.0, Bekker(p, b, z_max) - UnloadingSlope(p, b, z_max) * (z_max - z));
  };
  arc.sigma = [=, &p](double t) {
    const double z = z0 - r * (1.0 - std::cos(t));
    if (t < 0) return unloaded(z, deepest);
    return z >= rut ? Bekker(p, b, z) : unloaded(z, rut);
  };
  arc.tau = [=, &p, sigma = arc.sigma, front = arc.front](double t) {
    const double j = r * ((front - t) - (1 - slip) * (std::sin(front) - std::sin(t)));
    return (p.cohesion * 1e3 + sigma(t) * tan_phi) * (1 - std::exp(-j / p.shear_modulus));
  };
  return arc;
}

// The load alone (what RollingSinkage bisects on).
inline double RollingLoad(const model::SoilParameters& p, double r, double b, double z0,
                          double slip, double rut = 0.0, int intervals = kSimpsonIntervals) {
  const RollingArc a = RollingStresses(p, r, b, z0, slip, rut);
  return b * r *
         Simpson([&](double t) { return a.sigma(t) * std::cos(t) + a.tau(t) * std::sin(t); },
                 a.rear, a.front, intervals);
}

inline RollingWheelForces RollingWheel(const model::SoilParameters& p, double r, double b,
                                       double z0, double slip, double rut = 0.0,
                                       int intervals = kSimpsonIntervals) {
  const RollingArc a = RollingStresses(p, r, b, z0, slip, rut);
  RollingWheelForces out;
  out.load = RollingLoad(p, r, b, z0, slip, rut, intervals);
  out.pull = b * r *
             Simpson([&](double t) { return a.tau(t) * std::cos(t) - a.sigma(t) * std::sin(t); },
                     a.rear, a.front, intervals);
  out.compaction =
      b * r *
      Simpson([&](double t) { return a.sigma(t) * std::sin(t); }, a.rear, a.front, intervals);
  return out;
}

// The torque [N m] that wheel's shear resists its spin with (the driving
// torque it needs in a steady state): b r^2 times the integral of tau.
inline double RollingShearTorque(const model::SoilParameters& p, double r, double b, double z0,
                                 double slip, double rut = 0.0,
                                 int intervals = kSimpsonIntervals) {
  const RollingArc a = RollingStresses(p, r, b, z0, slip, rut);
  return b * r * r * Simpson(a.tau, a.rear, a.front, intervals);
}

// That wheel also slipping sideways, at slip angle alpha (its centre's
// side speed over its forward speed, tan alpha): the soil under a rim
// point is sheared along the rim by Wong and Reece's j_x and across it by
// j_y = r (1 - i) tan(alpha) (theta_f - theta) (the side speed times the
// time since the point entered the soil), and Janosi and Hanamoto's law
// takes the whole displacement in its direction (Wong, 2008, ch. 2.5,
// combined slip). The side force [N] is against the side speed.
struct SideSlipForces {
  double pull = 0;  // b r int (tau_x cos - sigma sin) [N]
  double side = 0;  // b r int tau_y, along the side speed [N] (negative)
};

inline SideSlipForces RollingWheelSideSlip(const model::SoilParameters& p, double r, double b,
                                           double z0, double slip, double tan_alpha,
                                           int intervals = kSimpsonIntervals) {
  const RollingArc a = RollingStresses(p, r, b, z0, slip, 0.0);
  const double tan_phi = std::tan(p.friction_angle * M_PI / 180);
  auto shear = [&](double t, bool across) {
    const double jx = r * ((a.front - t) - (1 - slip) * (std::sin(a.front) - std::sin(t)));
    const double jy = -r * (1 - slip) * tan_alpha * (a.front - t);
    const double j = std::hypot(jx, jy);
    if (j == 0) return 0.0;
    const double tau =
        (p.cohesion * 1e3 + a.sigma(t) * tan_phi) * (1 - std::exp(-j / p.shear_modulus));
    return tau * (across ? jy : jx) / j;
  };
  SideSlipForces out;
  out.pull = b * r *
             Simpson([&](double t) { return shear(t, false) * std::cos(t) - a.sigma(t) * std::sin(t); },
                     a.rear, a.front, intervals);
  out.side = b * r * Simpson([&](double t) { return shear(t, true); }, a.rear, a.front, intervals);
  return out;
}

// The sinkage at which that wheel carries `load` (bisection).
inline double RollingSinkage(const model::SoilParameters& p, double r, double b, double slip,
                             double load, double rut = 0.0, int intervals = kSimpsonIntervals) {
  double lo = rut > 0 ? rut - Bekker(p, b, rut) / UnloadingSlope(p, b, rut) : 0.0, hi = r;
  for (int k = 0; k < 50; ++k)
    (RollingLoad(p, r, b, 0.5 * (lo + hi), slip, rut, intervals) < load ? lo : hi) =
        0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// Bekker's compaction resistance of a rigid wheel sunk z0 (the work of
// pressing a rut z0 deep, per metre): b (k_c / b + k_phi) z0^(n+1) / (n+1).
inline double BekkerCompaction(const model::SoilParameters& p, double b, double z0) {
  return b * (p.k_c * 1e3 / b + p.k_phi * 1e3) * std::pow(z0, p.n + 1) / (p.n + 1);
}

// The same with the rebound behind the lowest point, which pushes the
// wheel forward: the unloading line from p0 = p(z0) to 0 over p0 / k_u
// gives back b p0^2 / (2 k_u). This is the normal stresses' resistance of
// Wong's rigid wheel whose rear unloads (RollingWheel's `compaction`), in
// closed form: with z = z0 - r (1 - cos theta), r sin(theta) dtheta = -dz.
inline double CompactionWithRebound(const model::SoilParameters& p, double b, double z0) {
  const double p0 = Bekker(p, b, z0);
  return BekkerCompaction(p, b, z0) - b * p0 * p0 / (2 * UnloadingSlope(p, b, z0));
}

}  // namespace simpartner::validate
