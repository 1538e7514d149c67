#include "simpartner/sim/soil_mechanics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace simpartner::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Below these a wheel neither spins nor moves: no shear displacement.
constexpr double kStillSpin = 1e-6;   // [rad/s]
constexpr double kStillSpeed = 1e-6;  // [m/s]
// A wheel dragged without turning: every rim point has slid far; the
// shear displacement is taken as this many K (1 - e^-40 of the strength).
constexpr double kSlidFar = 40.0;

// The wheel's own frame: its plane's up (the surface's up, less any
// component along the axle) and forward.
struct WheelFrame {
  Eigen::Vector3d up, forward;
  bool valid = false;
};

WheelFrame FrameOf(const WheelState& wheel, const SoilSurface& surface) {
  WheelFrame frame;
  const Eigen::Vector3d in_plane =
      surface.up - surface.up.dot(wheel.axle) * wheel.axle;
  if (in_plane.norm() < 1e-6) return frame;  // axle upright: not rolling on the soil
  frame.up = in_plane.normalized();
  frame.forward = frame.up.cross(wheel.axle).normalized();
  frame.valid = true;
  return frame;
}

double HeightAbove(const SoilSurface& surface, const Eigen::Vector3d& point) {
  return (point - surface.origin).dot(surface.up);
}

}  // namespace

Eigen::Vector2d SoilCoordinates(const SoilSurface& surface, const Eigen::Vector3d& point) {
  if (surface.keyed_apart) {
    const Eigen::Vector3d d = point - surface.key_origin;
    return {d.dot(surface.key_u), d.dot(surface.key_w)};
  }
  const Eigen::Vector3d d = point - surface.origin;
  return {d.dot(surface.u_axis), d.dot(surface.up.cross(surface.u_axis))};
}

namespace {

// The rim point at the angle whose cosine and sine these are.
Eigen::Vector3d RimPoint(const WheelState& wheel, const WheelFrame& frame, double cos_theta,
                         double sin_theta) {
  return wheel.centre + wheel.radius * (-cos_theta * frame.up + sin_theta * frame.forward);
}

// The midpoints of `samples` equal parts of [-half, half], with their
// cosines and sines by rotation (two calls to the library, not two per
// point: the sum's error grows by about 1e-16 a point).
struct ArcAngles {
  ArcAngles(double half, double step)
      : theta(-half + 0.5 * step),
        cos_theta(std::cos(theta)),
        sin_theta(std::sin(theta)),
        step_(step),
        cos_step_(std::cos(step)),
        sin_step_(std::sin(step)) {}
  void Next() {
    const double c = cos_theta * cos_step_ - sin_theta * sin_step_;
    sin_theta = sin_theta * cos_step_ + cos_theta * sin_step_;
    cos_theta = c;
    theta += step_;
    ++k;
  }
  double theta, cos_theta, sin_theta;
  int k = 0;

 private:
  double step_, cos_step_, sin_step_;
};

// The arc of the rim below the untouched surface: [-theta_max, theta_max].
double ArcHalfAngle(double sinkage, double radius, bool* stuck) {
  const double depth = std::min(sinkage, radius);
  *stuck = sinkage >= radius;
  return std::acos(1.0 - depth / radius);
}

// How far the rim point at theta (sine sin_theta) has sheared the soil
// since it entered it at theta_entry (sine sin_entry): the arc's front
// edge for a wheel spinning forward, its rear edge for one spinning
// backward (EntryAngle). Along the rim, Wong and Reece's
//   j_x = r (theta_e - theta) - (v / omega) (sin theta_e - sin theta);
// across it, the wheel's side speed v_y over the time the point has been
// in the soil, (theta_e - theta) / omega, against that speed:
//   j_y = -v_y (theta_e - theta) / omega.
// A wheel that does not turn has slid far wherever it moves.
struct Displacement {
  double along = 0.0, across = 0.0;
};

double SlidFar(const Soil& soil, double speed) {
  return std::abs(speed) > kStillSpeed ? -std::copysign(kSlidFar * soil.shear_modulus, speed) : 0.0;
}

// A wheel's speeds as the displacements need them, divided by the spin
// once a wheel rather than at every point (divisions were a fifth of a
// point's cost).
struct WheelMotion {
  WheelMotion(const Soil& soil, double radius, double v, double side_speed, double omega)
      : turning(std::abs(omega) > kStillSpin),
        r(radius),
        per_omega(turning ? 1.0 / omega : 0.0),
        v_per_omega(v * per_omega),
        side_per_omega(side_speed * per_omega),
        slid{SlidFar(soil, v), SlidFar(soil, side_speed)} {}
  bool turning;
  double r, per_omega, v_per_omega, side_per_omega;
  Displacement slid;  // not turning: the displacement everywhere
};

Displacement ShearDisplacement(const WheelMotion& m, double theta_entry, double sin_entry,
                               double theta, double sin_theta) {
  if (!m.turning) return m.slid;
  const double turned = theta_entry - theta;
  return {m.r * turned - m.v_per_omega * (sin_entry - sin_theta), -m.side_per_omega * turned};
}

// The shear stress along and across the rim per unit of strength
// c + sigma tan phi, after displacement d: Janosi and Hanamoto's law of
// the whole displacement |d|, in its direction (Wong's combined slip), so
// a side slip takes from the strength left for traction. The same at
// every point of a wheel that does not turn.
Displacement ShearPerStrength(const Soil& soil, const Displacement& d) {
  // Not std::hypot: its care for overflow costs a sixth of the soil's time.
  const double j = std::sqrt(d.along * d.along + d.across * d.across);
  if (j == 0.0) return {};
  const double per_j = (1.0 - std::exp(-j / soil.shear_modulus)) / j;
  return {per_j * d.along, per_j * d.across};
}

// The shear stress [Pa] at normal stress sigma after displacement d.
Displacement ShearStress(const Soil& soil, double sigma, const Displacement& d) {
  const double strength = soil.cohesion + sigma * soil.tan_phi;
  const Displacement unit = ShearPerStrength(soil, d);
  return {strength * unit.along, strength * unit.across};
}

// The shear stress at a rim point with its derivatives against the spin
// and against the side speed, for a wheel that turns: the displacement's
// derivatives are
//   d j_x / d omega = (v / omega^2)(sin theta_e - sin theta),
//   d j_y / d omega = v_y (theta_e - theta) / omega^2,
//   d j_y / d v_y = -(theta_e - theta) / omega,
// and tau = S (1 - e^(-j/K)) d / j gives
//   d tau = S (e^(-j/K) / K) dj d / j + S (1 - e^(-j/K)) (dd / j - d dj / j^2),
// dj = d . dd / j: one exp a point for the stress and both slopes.
struct ShearAt {
  Displacement tau, per_spin, per_side;
  double along_per_strength = 0.0;  // tau.along / (c + sigma tan phi)
};

ShearAt ShearWithSlopes(const Soil& soil, double per_k, double sigma, const Displacement& d,
                        const Displacement& d_per_spin, const Displacement& d_per_side) {
  const double strength = soil.cohesion + sigma * soil.tan_phi;
  ShearAt out;
  const double j = std::sqrt(d.along * d.along + d.across * d.across);
  if (j == 0.0) {  // the law's slope at 0: S / K
    const double s_per_k = strength * per_k;
    out.per_spin = {s_per_k * d_per_spin.along, s_per_k * d_per_spin.across};
    out.per_side = {s_per_k * d_per_side.along, s_per_k * d_per_side.across};
    return out;
  }
  const double inverse_j = 1.0 / j;
  const double e = std::exp(-j * per_k), g_per_j = (1.0 - e) * inverse_j;
  const double f_per_j = strength * g_per_j;
  const Displacement unit{d.along * inverse_j, d.across * inverse_j};
  out.tau = {f_per_j * d.along, f_per_j * d.across};
  out.along_per_strength = g_per_j * d.along;
  const double e_per_k = strength * e * per_k;
  auto derivative = [&](const Displacement& dd) {
    const double dj = unit.along * dd.along + unit.across * dd.across;
    // d tau = (df - f / j dj) unit + f / j dd
    const double radial = e_per_k * dj - f_per_j * dj;
    return Displacement{radial * unit.along + f_per_j * dd.along,
                        radial * unit.across + f_per_j * dd.across};
  };
  out.per_spin = derivative(d_per_spin);
  out.per_side = derivative(d_per_side);
  return out;
}

// Where the rim's points enter the loaded arc at spin omega.
double EntryAngle(const WheelSoilForces& out, double omega) {
  return omega >= 0.0 ? out.theta_front : out.theta_rear;
}

double Slip(double radius, double v, double omega) {
  const double rim = radius * omega;
  if (std::abs(rim) >= std::abs(v) && std::abs(rim) > kStillSpeed) return 1.0 - v / rim;
  if (std::abs(v) > kStillSpeed) return rim / v - 1.0;
  return 0.0;
}

}  // namespace

Soil Soil::From(const model::SoilParameters& p) {
  Soil soil;
  soil.n = p.n;
  soil.k_c = p.k_c * 1e3;      // kN/m^(n+1) -> N/m^(n+1)
  soil.k_phi = p.k_phi * 1e3;  // kN/m^(n+2) -> N/m^(n+2)
  soil.cohesion = p.cohesion * 1e3;
  soil.tan_phi = std::tan(p.friction_angle * kPi / 180.0);
  soil.shear_modulus = p.shear_modulus;
  soil.unloading_stiffness = p.unloading_stiffness * 1e3;
  soil.unloading_growth = p.unloading_growth * 1e3;  // kPa/m^2 -> Pa/m^2
  soil.viscosity = p.viscosity * 1e3;
  return soil;
}

double Soil::Pressure(double z, double b) const {
  return z > 0.0 ? (k_c / b + k_phi) * std::pow(z, n) : 0.0;
}

double Soil::UnloadingSlope(double z_max, double p_max) const {
  const double wong = unloading_stiffness + unloading_growth * z_max;
  return z_max > 0.0 ? std::max(wong, std::max(1.0, n) * p_max / z_max) : wong;
}

SoilMemory::SoilMemory(double cell_size) : cell_size_(cell_size), per_cell_(1.0 / cell_size) {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size))
    throw std::invalid_argument("soil memory: a cell of " + std::to_string(cell_size) +
                                " m, not a positive size");
}

namespace {

// floor(x) as an integer, inline (std::floor is a library call here).
int64_t FloorToInt(double x) {
  const auto i = static_cast<int64_t>(x);
  return static_cast<double>(i) > x ? i - 1 : i;
}

}  // namespace

uint64_t SoilMemory::Key(double u, double w) const {
  // Two's complement cell indices, 32 bits each (shifting a negative
  // signed value is undefined).
  const auto iu = static_cast<uint64_t>(FloorToInt(u * per_cell_));
  const auto iw = static_cast<uint64_t>(FloorToInt(w * per_cell_));
  return (iu << 32) ^ (iw & 0xffffffffULL);
}

SoilMemory::Depth* SoilMemory::Find(uint64_t key) {
  if (Depth* cached = cache_.Find(key)) return cached;
  const auto it = deepest_.find(key);
  if (it == deepest_.end()) return nullptr;
  cache_.Put(key, &it->second);
  return &it->second;
}

SoilMemory::Depth& SoilMemory::Entry(uint64_t key) {
  if (Depth* found = Find(key)) return *found;
  Depth& made = deepest_[key];  // references into the map stay valid as it grows
  cache_.Put(key, &made);
  return made;
}

SoilMemory::Depth SoilMemory::At(double u, double w) const {
  const auto it = deepest_.find(Key(u, w));
  return it == deepest_.end() ? Depth{} : it->second;
}

void SoilMemory::Press(double u, double w, double z, double z_n) {
  PathPress press(this);
  if (z > press.Cell(u, w).z) press.Deepen(z, z_n);
}

size_t SoilMemory::ForgetOldest(size_t most) {
  if (deepest_.size() <= most) return 0;
  const size_t keep = most - most / 4, forget = deepest_.size() - keep;
  std::vector<uint64_t> paths;
  paths.reserve(deepest_.size());
  for (const auto& [key, depth] : deepest_) paths.push_back(depth.path);
  std::nth_element(paths.begin(), paths.begin() + static_cast<std::ptrdiff_t>(forget - 1), paths.end());
  cache_.Clear();
  const uint64_t newest_forgotten = paths[forget - 1];
  size_t forgotten = 0;
  for (auto it = deepest_.begin(); it != deepest_.end() && forgotten < forget;) {
    if (it->second.path <= newest_forgotten) {
      it = deepest_.erase(it);
      ++forgotten;
    } else {
      ++it;
    }
  }
  return forgotten;
}

SoilMemory::Depth SoilMemory::PathPress::Before(uint64_t key, const Depth* entry) const {
  if (!entry) return Depth{};
  if (entry->path != path_) return *entry;
  for (int k = deepened_count_ - 1; k >= 0; --k) {
    const Deepened& d = deepened_[static_cast<size_t>(k)];
    if (d.key == key) return Depth{d.z, d.z_n, 0};
  }
  return *entry;  // not reached: a cell of this path is in its list
}

const SoilMemory::Depth& SoilMemory::PathPress::Cell(double u, double w) {
  const uint64_t key = memory_->Key(u, w);
  if (!in_cell_ || key != key_) {
    in_cell_ = true;
    key_ = key;
    deepest_ = memory_->Find(key_);
    before_ = Before(key_, deepest_);
  }
  return before_;
}

void SoilMemory::PathPress::Deepen(double z, double z_n) {
  if (!(z > 0.0)) return;
  if (deepest_ && z <= deepest_->z) return;
  if (!deepest_ || deepest_->path != path_) {
    if (deepened_count_ == kMaxPathCells)
      throw std::length_error("soil memory: a path deepens more than " +
                              std::to_string(kMaxPathCells) + " cells");
    deepened_[static_cast<size_t>(deepened_count_++)] = {key_, before_.z, before_.z_n};
  }
  if (!deepest_) deepest_ = &memory_->Entry(key_);
  *deepest_ = Depth{z, z_n, path_};
}

PressureOnSoil PressureWithMemory(const Soil& soil, double z, const SoilMemory::Depth& before,
                                  double b) {
  const double k = soil.k_c / b + soil.k_phi;
  PressureOnSoil out;
  if (z >= before.z) {  // on Bekker's curve: the one pow of the point
    out.loading = true;
    if (z <= 0.0) return out;
    // At the deepest press exactly (a wheel that has not moved), its z^n.
    out.z_n = z == before.z ? before.z_n : std::pow(z, soil.n);
    out.pressure = k * out.z_n;
    out.slope = soil.n * out.pressure / z;
    return out;
  }
  const double p_max = k * before.z_n, k_u = soil.UnloadingSlope(before.z, p_max);
  out.pressure = std::max(0.0, p_max - k_u * (before.z - z));
  if (out.pressure > 0.0) out.slope = k_u;
  return out;
}

double PressureWithMemory(const Soil& soil, double z, double z_max, double b) {
  const double z_n = z_max > 0.0 ? std::pow(z_max, soil.n) : 0.0;
  return PressureWithMemory(soil, z, SoilMemory::Depth{z_max, z_n, 0}, b).pressure;
}

namespace {

// The spin step [rad/s] and side speed step [m/s] of the differences that
// give the shear's slopes.
constexpr double kSpinStep = 1e-3;
constexpr double kSideStep = 1e-3;

// One point of the arc: its angle, the part of the arc it stands for
// (centred on it), and the normal stress there and its slope against
// sinkage.
struct ArcSample {
  double theta, cos_theta, sin_theta;
  double width;   // [rad]
  double sigma;   // [Pa]
  double dsigma;  // d sigma / dz [Pa/m]
  bool bearing;   // the soil pushes here at rest (sigma before its damping > 0)
};

// The soil's memory as an evaluation sees it: read only, or pressed by
// the rim as it goes.
struct ArcMemory {
  const SoilMemory& read;
  SoilMemory::PathPress* pressed = nullptr;  // read through it, as the memory was
  bool press = true;                         // and press it
};

// How fast the rim point at theta sinks (its velocity against the
// surface's up): -(v + omega x (p - c)) . up with p - c = r (-cos theta
// u + sin theta f) (u, f the wheel frame's up and forward), i.e.
// -(v . up) + r cos theta omega . (u x up) - r sin theta omega . (f x up):
// three numbers a wheel, two products a point.
struct SinkingRate {
  SinkingRate(const WheelState& wheel, const WheelFrame& frame, const Eigen::Vector3d& up)
      : centre(-wheel.velocity.dot(up)),
        per_cos(wheel.radius * wheel.angular_velocity.dot(frame.up.cross(up))),
        per_sin(-wheel.radius * wheel.angular_velocity.dot(frame.forward.cross(up))) {}
  double At(double cos_theta, double sin_theta) const {
    return centre + per_cos * cos_theta + per_sin * sin_theta;
  }
  double centre, per_cos, per_sin;
};

// The normal stress at `point` of the rim, and its slope against sinkage.
// With `press`, the memory records the point (ArcMemory).
void NormalStress(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                  const ArcMemory& memory, const Eigen::Vector3d& point, double sinking,
                  ArcSample* sample) {
  const double z = -HeightAbove(surface, point);
  const Eigen::Vector2d at = SoilCoordinates(surface, point);
  const SoilMemory::Depth before =
      memory.pressed ? memory.pressed->Cell(at.x(), at.y()) : memory.read.At(at.x(), at.y());
  double s = 0.0, ds = 0.0;
  if (z > 0.0) {
    const PressureOnSoil p = PressureWithMemory(soil, z, before, wheel.width);
    if (p.loading && memory.pressed && memory.press) memory.pressed->Deepen(z, p.z_n);
    s = p.pressure;
    ds = p.slope;
  }
  // The soil's damping: on any loaded point, sinking or rising.
  sample->bearing = s > 0.0;
  if (s > 0.0) s = std::max(0.0, s + soil.viscosity * sinking);
  if (s == 0.0) ds = 0.0;
  sample->sigma = s;
  sample->dsigma = ds;
}

// The stresses summed over the loaded arc into `out` (normal and shear
// force, torque, side force, strength, area), and the slopes the
// contact's rows need: the stresses' against sinking further (along
// `up`: Bekker's or the unloading line's slope, and the shear's share, its
// strength c + sigma tan phi growing with sigma), the thrust's (along the
// rolling direction) against the spin and the side force's against the
// side speed. A wheel that does not turn (its shear is that of a long
// slide, whatever the speed) takes the last two by differences.
struct ArcSums {
  double stiffness = 0.0, thrust_per_spin = 0.0, side_per_side_speed = 0.0;
};

ArcSums SumOverArc(const Soil& soil, const WheelState& wheel, const WheelFrame& frame,
                   const Eigen::Vector3d& up, const ArcSample* arc, int samples,
                   WheelSoilForces* out) {
  const double r = wheel.radius, v = out->forward_speed, v_y = out->side_speed, w = out->spin;
  const WheelMotion motion(soil, r, v, v_y, w);
  const double per_k = 1.0 / soil.shear_modulus;
  // Turning: the displacement's slopes against the spin, over the
  // displacement's own factors (ShearWithSlopes).
  const double v_per_omega2 = motion.v_per_omega * motion.per_omega;
  const double side_per_omega2 = motion.side_per_omega * motion.per_omega;
  const double entry = EntryAngle(*out, w), sin_entry = std::sin(entry);
  const double faster_entry = EntryAngle(*out, w + kSpinStep);
  const double sin_faster_entry = std::sin(faster_entry);
  // Not turning: the motion spun kSpinStep faster, and the shear at the
  // wheel's speeds and at a side speed kSideStep faster, per unit of
  // strength (the shears found only for such a wheel: each costs an exp).
  const bool still_wheel = !motion.turning;
  const Displacement still = still_wheel ? ShearPerStrength(soil, motion.slid) : Displacement{};
  const Displacement sideways_still =
      still_wheel ? ShearPerStrength(soil, {SlidFar(soil, v), SlidFar(soil, v_y + kSideStep)})
                  : Displacement{};
  const WheelMotion faster(soil, r, v, v_y, w + kSpinStep);
  ArcSums sums;
  for (const ArcSample* a_point = arc; a_point != arc + samples; ++a_point) {
    const ArcSample& a = *a_point;
    if (a.sigma <= 0.0) continue;
    const double area = wheel.width * r * a.width;
    const double strength = soil.cohesion + a.sigma * soil.tan_phi;
    ShearAt at;
    if (motion.turning) {
      const double turned = entry - a.theta;
      at = ShearWithSlopes(soil, per_k, a.sigma,
                           ShearDisplacement(motion, entry, sin_entry, a.theta, a.sin_theta),
                           {v_per_omega2 * (sin_entry - a.sin_theta), side_per_omega2 * turned},
                           {0.0, -turned * motion.per_omega});
    } else {
      at.tau = {strength * still.along, strength * still.across};
      at.along_per_strength = still.along;
      const Displacement faster_tau = ShearStress(
          soil, a.sigma,
          ShearDisplacement(faster, faster_entry, sin_faster_entry, a.theta, a.sin_theta));
      at.per_spin = {(faster_tau.along - at.tau.along) / kSpinStep, 0.0};
      at.per_side = {0.0, (strength * sideways_still.across - at.tau.across) / kSideStep};
    }
    const Eigen::Vector3d inward = a.cos_theta * frame.up - a.sin_theta * frame.forward;
    const Eigen::Vector3d tangent = a.cos_theta * frame.forward + a.sin_theta * frame.up;
    out->normal_force += a.sigma * area * inward;
    out->shear_force += area * (at.tau.along * tangent + at.tau.across * wheel.axle);
    out->shear_torque += r * at.tau.along * area;
    out->side_force += at.tau.across * area;
    out->shear_strength += strength * area;
    out->contact_area += area;
    const double dtau = at.along_per_strength * soil.tan_phi;
    sums.stiffness += a.dsigma * area * (inward.dot(up) + dtau * tangent.dot(up));
    sums.thrust_per_spin += at.per_spin.along * area * a.cos_theta;
    sums.side_per_side_speed += at.per_side.across * area;
  }
  return sums;
}

// The normal stress at any angle of one wheel's arc, this step.
struct ArcPoints {
  const Soil& soil;
  const WheelState& wheel;
  const SoilSurface& surface;
  const WheelFrame& frame;
  const SinkingRate& sinking;

  // Into `a` (in place: a copy of the sample cost a tenth of the pass).
  void At(const ArcMemory& memory, double theta, double cos_theta, double sin_theta,
          double width, ArcSample* a) const {
    a->theta = theta;
    a->cos_theta = cos_theta;
    a->sin_theta = sin_theta;
    a->width = width;
    NormalStress(soil, wheel, surface, memory, RimPoint(wheel, frame, cos_theta, sin_theta),
                 sinking.At(cos_theta, sin_theta), a);
  }
  // The part [lo, hi] of the arc, read only: where the loaded arc ends
  // is sought after the pass, on the memory as it was before it.
  ArcSample At(const ArcMemory& memory, double lo, double hi) const {
    const double theta = 0.5 * (lo + hi);
    ArcSample a;
    At(ArcMemory{memory.read, memory.pressed, false}, theta, std::cos(theta), std::sin(theta),
       hi - lo, &a);
    return a;
  }
};

// Bisections that find where the loaded arc ends between two points:
// to 2^-6 of the points' spacing (0.03 deg at 64 points on a quarter
// turn; on snow 2 % of the rebound's sliver, whose load is a few % of
// the wheel's).
constexpr int kEndBisections = 6;

// The angle between `loaded` and `unloaded` where the normal stress ends.
double LoadedEnd(const ArcPoints& points, const ArcMemory& memory, double loaded,
                 double unloaded) {
  for (int i = 0; i < kEndBisections; ++i) {
    const double mid = 0.5 * (loaded + unloaded);
    (points.At(memory, mid, mid).bearing ? loaded : unloaded) = mid;
  }
  return 0.5 * (loaded + unloaded);
}

// The midpoint rule counts a point's whole part of the arc as loaded or
// not by the point alone. Where the loaded arc ends inside a part, that
// errs by up to a part's load: behind a rolling wheel the soil's rebound
// ends in a sliver narrower than a part (about 1.8 deg on snow against
// 1.95 at 64 points), which the points alone cannot place. Each end between two
// points is found, and the loaded piece of the part it cuts stands in for
// that part, at the piece's midpoint. A part without its point loaded may
// gain a piece from each side: those pieces are added after the `samples`
// points. Returns the number of points.
int CutAtLoadedEnds(const ArcPoints& points, const ArcMemory& memory, ArcSample* arc,
                    int samples) {
  int count = samples;
  auto loaded = [&](int k) { return arc[k].bearing; };
  for (int k = 0; k + 1 < samples; ++k) {
    if (loaded(k) == loaded(k + 1)) continue;
    const ArcSample& a = arc[k];
    ArcSample& b = arc[k + 1];
    const double border = a.theta + 0.5 * a.width;
    const double end = loaded(k) ? LoadedEnd(points, memory, a.theta, b.theta)
                                 : LoadedEnd(points, memory, b.theta, a.theta);
    if (loaded(k) && end < border) {  // a's part, up to the end
      arc[k] = points.At(memory, a.theta - 0.5 * a.width, end);
    } else if (loaded(k)) {  // and the start of b's
      arc[count++] = points.At(memory, border, end);
    } else if (end > border) {  // b's part, from the end
      b = points.At(memory, end, b.theta + 0.5 * b.width);
    } else {  // and the end of a's
      arc[count++] = points.At(memory, end, border);
    }
  }
  return count;
}

// The arc's points straddle its lowest point, which a rolling wheel's
// rim passes over every cell of its track: without it the track would
// keep r (1 - cos(step / 2)) less than the sinkage (0.044 mm on snow at 64
// points), and the rebound behind the wheel would start that much
// higher and reach 14 % further back.
void PressPoint(const SoilSurface& surface, const Eigen::Vector3d& point, double exponent,
                SoilMemory::PathPress* press) {
  const Eigen::Vector2d at = SoilCoordinates(surface, point);
  const double z = -HeightAbove(surface, point);
  if (z > press->Cell(at.x(), at.y()).z) press->Deepen(z, std::pow(z, exponent));
}

void PressLowest(const WheelState& wheel, const WheelFrame& frame, const SoilSurface& surface,
                 double exponent, SoilMemory::PathPress* press) {
  PressPoint(surface, wheel.centre - wheel.radius * frame.up, exponent, press);
}

void CheckSamples(int samples) {
  if (samples < 1 || samples > kMaxArcSamples)
    throw std::invalid_argument("soil: " + std::to_string(samples) + " arc samples, not 1 to " +
                                std::to_string(kMaxArcSamples));
}

// The soil's answer to `wheel` (soil_mechanics.h: WheelOnSoil).
WheelSoilForces Evaluate(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                         const ArcMemory& memory, int samples, WheelSoilSlopes* slopes) {
  CheckSamples(samples);
  WheelSoilForces out;
  if (slopes) *slopes = WheelSoilSlopes{};
  const WheelFrame frame = FrameOf(wheel, surface);
  if (!frame.valid) return out;
  const double r = wheel.radius;
  out.sinkage = -HeightAbove(surface, wheel.centre - r * frame.up);
  if (out.sinkage <= 0.0) return out;
  const double half = ArcHalfAngle(out.sinkage, r, &out.stuck);
  out.forward_speed = wheel.velocity.dot(frame.forward);
  out.spin = -wheel.angular_velocity.dot(wheel.axle);
  out.slip = Slip(r, out.forward_speed, out.spin);

  // Normal stresses first: where the arc is loaded decides theta_front.
  const double step = 2.0 * half / samples;
  // Each end of the loaded arc may add a point (CutAtLoadedEnds).
  std::array<ArcSample, 2 * kMaxArcSamples> arc;
  const SinkingRate sinking(wheel, frame, surface.up);
  const ArcPoints points{soil, wheel, surface, frame, sinking};
  for (ArcAngles angles(half, step); angles.k < samples; angles.Next())
    points.At(memory, angles.theta, angles.cos_theta, angles.sin_theta, step,
              &arc[static_cast<size_t>(angles.k)]);
  if (memory.pressed) PressLowest(wheel, frame, surface, soil.n, memory.pressed);
  const int count = CutAtLoadedEnds(points, memory, arc.data(), samples);
  out.theta_front = -half;
  out.theta_rear = half;
  for (int k = 0; k < count; ++k) {
    const ArcSample& a = arc[static_cast<size_t>(k)];
    if (a.sigma <= 0.0) continue;
    out.theta_front = std::max(out.theta_front, a.theta + 0.5 * a.width);
    out.theta_rear = std::min(out.theta_rear, a.theta - 0.5 * a.width);
  }
  out.side_speed = wheel.velocity.dot(wheel.axle);
  const ArcSums sums = SumOverArc(soil, wheel, frame, surface.up, arc.data(), count, &out);
  out.touching = out.contact_area > 0.0;
  if (slopes) {
    slopes->stiffness = sums.stiffness;
    slopes->thrust_slope = sums.thrust_per_spin / -r;  // the slip velocity v - r omega
    slopes->side_slope = sums.side_per_side_speed;
  }
  return out;
}

}  // namespace

WheelSoilForces WheelOnSoil(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                            const SoilMemory& memory, int samples, WheelSoilSlopes* slopes) {
  return Evaluate(soil, wheel, surface, ArcMemory{memory}, samples, slopes);
}

WheelSoilForces PressWheelOnSoil(const Soil& soil, const WheelState& wheel,
                                 const SoilSurface& surface, SoilMemory* memory, int samples,
                                 WheelSoilSlopes* slopes) {
  SoilMemory::PathPress press(memory);
  return Evaluate(soil, wheel, surface, ArcMemory{*memory, &press}, samples, slopes);
}

void PressWheel(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                SoilMemory* memory, int samples) {
  CheckSamples(samples);
  const WheelFrame frame = FrameOf(wheel, surface);
  if (!frame.valid) return;
  const double sinkage = -HeightAbove(surface, wheel.centre - wheel.radius * frame.up);
  if (sinkage <= 0.0) return;
  bool stuck = false;
  const double half = ArcHalfAngle(sinkage, wheel.radius, &stuck);
  const double step = 2.0 * half / samples;
  SoilMemory::PathPress press(memory);
  for (ArcAngles angles(half, step); angles.k < samples; angles.Next())
    PressPoint(surface, RimPoint(wheel, frame, angles.cos_theta, angles.sin_theta), soil.n, &press);
  PressLowest(wheel, frame, surface, soil.n, &press);
}

}  // namespace simpartner::sim
