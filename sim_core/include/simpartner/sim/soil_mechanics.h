// Wheel-soil mechanics (docs/soil.md): the stresses a rigid
// wheel meets on soft soil, from the state of this step.
//
// Along the wheel's rim in its mid-plane, from where it enters the soil
// (theta_f, ahead of the lowest point) to where it leaves it (theta_r,
// behind), each element of the rim carries
//   - a normal stress sigma, Bekker's p = (k_c / b + k_phi) z^n where the
//     soil there is pressed deeper than ever before (loading), or on its
//     unloading line p_max - k_u (z_max - z) where it was pressed deeper
//     before (a rut: the wheel's rear, a second pass), never below 0, k_u
//     growing with z_max (Soil::UnloadingSlope),
//     plus the soil's viscosity times the rate the point sinks (or minus,
//     rising) where it is loaded;
//   - a shear stress tau, Janosi and Hanamoto's (c + sigma tan phi)
//     (1 - exp(-|j| / K)), j the shear displacement the rim point has
//     built up since it entered the soil (Wong and Reece):
//       j(theta) = r (theta_e - theta) - (v / omega) (sin theta_e - sin theta),
//     theta_e the edge where the rim enters the soil: the front edge
//     theta_f spinning forward, the rear edge theta_r spinning backward;
//     a wheel that also moves along its axle at v_y shears the soil
//     across too, j_y = -v_y (theta_e - theta) / omega (its speed over the
//     time the point has been in the soil), and the law takes the whole
//     displacement |(j, j_y)| in its direction (Wong's combined slip).
// Summed over the loaded arc (the wheel's width b times r dtheta) they
// are the soil's force on the wheel. The soil remembers how deep it was
// pressed (SoilMemory), so ruts stay and a second pass meets soil already
// compacted.
//
// Conventions: "up" is the soil surface's normal; "forward" is up x axle,
// the direction a wheel spinning at a positive rate omega (about -axle)
// rolls; theta is measured from the lowest point, positive forward.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <unordered_map>

#include "simpartner/model/model.h"

namespace simpartner::sim {

// A soil's figures in SI units (N, m, Pa), from the files' units.
struct Soil {
  double n = 1.0;
  double k_c = 0.0;                  // [N / m^(n+1)]
  double k_phi = 0.0;                // [N / m^(n+2)]
  double cohesion = 0.0;             // [Pa]
  double tan_phi = 0.0;              // [-]
  double shear_modulus = 0.01;       // K [m]
  double unloading_stiffness = 0.0;  // k_0 [Pa / m]
  double unloading_growth = 0.0;     // A_u [Pa / m^2]
  double viscosity = 0.0;            // [Pa s / m]

  static Soil From(const model::SoilParameters& parameters);
  // Bekker's pressure [Pa] at sinkage z [m] under a plate of width b [m].
  double Pressure(double z, double b) const;
  // The slope [Pa/m] of the unloading line below a deepest sinkage z_max
  // [m] that was pressed to p_max [Pa]: Wong's k_u = k_0 + A_u z_max, and
  // never shallower than Bekker's curve's steepest chord below z_max,
  // max(1, n) p_max / z_max, so that unloading and loading never cross.
  double UnloadingSlope(double z_max, double p_max) const;
};

// How deep one soil has been pressed, on a square grid of the ground
// (coordinates along the surface): per cell, the deepest sinkage below the
// untouched surface so far and its power n (Bekker's exponent, given by
// whoever presses), so that a point on the unloading line needs no pow.
// Cells nothing has touched are not stored.
//
// A cell holds one depth, so a rim point reads the depth its neighbour in
// the cell pressed, off by the rim's slope times the cell: 2 mm cells made
// a wheel settling into clay meet 1 % less load than Bekker's. The cells
// are 0.5 mm. A plane per cell (the pressing rim's slope) would remove
// the error at 2 mm, but gives the soil a sideways stiffness that a
// resting wheel, undamped sideways, turned into a growing roll.
class SoilMemory {
 public:
  // A cell's deepest press.
  struct Depth {
    double z = 0.0, z_n = 0.0;  // [m], z^n
    uint64_t path = 0;          // the PathPress that set it last
  };
  // The most cells one PathPress deepens.
  static constexpr int kMaxPathCells = 1024;
  explicit SoilMemory(double cell_size = 0.0005);
  double cell_size() const { return cell_size_; }
  // The deepest sinkage [m] at (u, w) so far, and its z^n; 0 where
  // untouched.
  Depth At(double u, double w) const;
  double Deepest(double u, double w) const { return At(u, w).z; }
  // Records sinkage z (z_n = z^n) at (u, w) when it is deeper than the
  // deepest so far.
  void Press(double u, double w, double z, double z_n);
  size_t cells() const { return deepest_.size(); }
  // Bounds the memory: past `most` cells it forgets those pressed longest
  // ago, down to three quarters of `most`, and returns how many it forgot.
  // Call it between evaluations (a PathPress holds pointers into it).
  size_t ForgetOldest(size_t most);

  // Pressing along a path (a rim's points, in order): each point reads
  // what its cell held before the path, however many of the path's points
  // fall in that cell and whenever it is read, and the cell keeps the
  // deepest of them. One lookup per cell, in the path's order.
  class PathPress {
   public:
    explicit PathPress(SoilMemory* memory) : memory_(memory), path_(++memory->paths_) {}
    // The deepest sinkage at (u, w) before the path, and its z^n.
    const Depth& Cell(double u, double w);
    // Records sinkage z (z_n = z^n) in the cell last read, when deeper.
    // std::length_error past kMaxPathCells cells.
    void Deepen(double z, double z_n);

   private:
    // What the cell of `key` (held at `entry`, or not stored) was before
    // the path.
    Depth Before(uint64_t key, const Depth* entry) const;

    SoilMemory* memory_;
    uint64_t path_;
    bool in_cell_ = false;
    uint64_t key_ = 0;
    Depth before_;
    Depth* deepest_ = nullptr;  // the cell's entry, once it has one
    // The cells the path deepened, as they were before it (left
    // uninitialised: a path begins at every wheel's step).
    struct Deepened {
      uint64_t key;
      double z, z_n;
    };
    std::array<Deepened, kMaxPathCells> deepened_;
    int deepened_count_ = 0;
  };

 private:
  // Where recently read cells are held in the map, direct-mapped by key:
  // a wheel's arc reads much the same cells step after step, and the
  // map's lookup (a division by its prime bucket count, then a chain)
  // was a fifth of a wheel's evaluation. Only cells the map holds are
  // cached, and the map's nodes stay put as it grows; forgetting clears
  // the cache, and a copy or a move starts with it empty.
  class CellCache {
   public:
    CellCache() { Clear(); }
    CellCache(const CellCache&) : CellCache() {}
    CellCache& operator=(const CellCache&) {
      Clear();
      return *this;
    }
    // The cached entry of `key`, or nullptr.
    Depth* Find(uint64_t key) const {
      const Line& line = lines_[Index(key)];
      return line.entry && line.key == key ? line.entry : nullptr;
    }
    void Put(uint64_t key, Depth* entry) { lines_[Index(key)] = {key, entry}; }
    void Clear() { lines_.fill(Line{}); }

   private:
    static constexpr int kBits = 11;  // 2048 lines, 32 kB
    static size_t Index(uint64_t key) {
      return static_cast<size_t>((key * 0x9E3779B97F4A7C15ULL) >> (64 - kBits));
    }
    struct Line {
      uint64_t key = 0;
      Depth* entry = nullptr;
    };
    std::array<Line, size_t{1} << kBits> lines_;
  };

  uint64_t Key(double u, double w) const;
  // The entry of `key`, or nullptr where the cell is untouched.
  Depth* Find(uint64_t key);
  // The entry of `key`, made (untouched) where there is none.
  Depth& Entry(uint64_t key);
  double cell_size_;
  double per_cell_;     // 1 / cell_size_
  uint64_t paths_ = 0;  // PathPresses begun
  std::unordered_map<uint64_t, Depth> deepest_;
  CellCache cache_;
};

// The pressure of soil pressed to z where it was pressed before as
// `before` says, under a plate of width b: Bekker's curve when z >=
// before.z (then `loading`, and z_n = z^n for the memory; 0 where z <= 0),
// its unloading line below, never negative; and its slope against sinking
// further (0 where the pressure is 0). The one rule of wheels and plates.
struct PressureOnSoil {
  double pressure = 0.0;  // [Pa]
  double slope = 0.0;     // [Pa/m]
  bool loading = false;
  double z_n = 0.0;       // z^n when loading
};
PressureOnSoil PressureWithMemory(const Soil& soil, double z, const SoilMemory::Depth& before,
                                  double b);
// Its pressure [Pa] where the soil was pressed to z_max before.
double PressureWithMemory(const Soil& soil, double z, double z_max, double b);

// A rigid wheel and its motion, in world coordinates.
struct WheelState {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d axle = Eigen::Vector3d::UnitZ();  // unit
  double radius = 0.3;                              // [m]
  double width = 0.2;                               // [m] the tread, b
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // of the centre [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // [rad/s]
};

// A flat patch of untouched soil: its surface is the plane through
// `origin` with normal `up` (unit). u and w, the memory's coordinates,
// are along `u_axis` and up x u_axis.
struct SoilSurface {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  Eigen::Vector3d u_axis = Eigen::Vector3d::UnitX();
  // A heightfield's tangent plane under one wheel: the memory is keyed in
  // the field's own frame (along key_u and key_w from key_origin), which
  // every wheel and step share, not in the plane's.
  bool keyed_apart = false;
  Eigen::Vector3d key_origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d key_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d key_w = Eigen::Vector3d::UnitZ();
};

// Where `point` is in the memory's grid (u, w) [m].
Eigen::Vector2d SoilCoordinates(const SoilSurface& surface, const Eigen::Vector3d& point);

// The soil's answer to a wheel, this step.
struct WheelSoilForces {
  bool touching = false;
  // Sunk to its axle or deeper: the arc is cut at a quarter turn each way
  // and the figures are those of a wheel sunk to its radius.
  bool stuck = false;
  double sinkage = 0.0;      // lowest rim point below the untouched surface [m]
  double theta_front = 0.0;  // where the loaded arc begins [rad], >= 0
  double theta_rear = 0.0;   // where it ends [rad], <= 0
  double forward_speed = 0.0;  // v [m/s]
  double spin = 0.0;           // omega [rad/s], positive rolling forward
  double slip = 0.0;           // i: 1 - v / (r omega) driving, r omega / v - 1 braking
  Eigen::Vector3d normal_force = Eigen::Vector3d::Zero();  // of the normal stresses [N]
  Eigen::Vector3d shear_force = Eigen::Vector3d::Zero();   // of the shear stresses [N]
  // The shear force the loaded arc could give at most, sum of
  // (c + sigma tan phi) dA [N], and the loaded area [m^2].
  double shear_strength = 0.0;
  double contact_area = 0.0;
  // Torque of the shear stresses about the axle [N m] (resisting a
  // driven wheel's spin: negative along the spin's sense).
  double shear_torque = 0.0;
  // The wheel's speed along its axle [m/s], and the shear's force along
  // the axle [N] (against that speed: the side force).
  double side_speed = 0.0;
  double side_force = 0.0;

  Eigen::Vector3d Force() const { return normal_force + shear_force; }
};

// How the soil's answer changes with the wheel's motion, for a contact
// that solves it implicitly (ode_soil.h).
struct WheelSoilSlopes {
  // d(F . up) / d(sinkage) [N/m]: the stresses' slope as the wheel sinks
  // further, on the same arc (where the soil is loaded: Bekker's slope,
  // or the unloading line's in a rut).
  double stiffness = 0.0;
  // d(shear force . forward) / d(slip velocity) [N s/m], the slip
  // velocity v - r omega of the lowest rim point, by a difference in spin
  // (kSpinStep of soil_mechanics.cpp; the viscosity's share is left out).
  double thrust_slope = 0.0;
  // d(side force) / d(side speed) [N s/m], by a difference in side speed.
  double side_slope = 0.0;
};

// The most points an evaluation takes along the arc.
constexpr int kMaxArcSamples = 512;

// The stresses on `wheel` from `soil` under `surface`, pressed before as
// `memory` (of this soil's n) says; `samples` points along the arc
// (midpoint rule, 1 to kMaxArcSamples; std::invalid_argument else), and,
// when `slopes` is given, their slopes in the same pass. The wheel's
// mid-plane is taken upright (its axle along the surface).
WheelSoilForces WheelOnSoil(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                            const SoilMemory& memory, int samples = 64,
                            WheelSoilSlopes* slopes = nullptr);

// WheelOnSoil and PressWheel at once, in one pass over the arc: the forces
// on `memory` as it was, which pressing the rim's points first would not
// change (where a point is pressed deeper it is on Bekker's curve either
// way), and `memory` records the rim where it is now. A contact calls it
// at the start of each step, so the soil holds every state's ruts.
WheelSoilForces PressWheelOnSoil(const Soil& soil, const WheelState& wheel,
                                 const SoilSurface& surface, SoilMemory* memory, int samples = 64,
                                 WheelSoilSlopes* slopes = nullptr);

// Records in `memory` how deep `wheel` presses `soil` now (the arc's
// points below the untouched surface), so that later steps see the rut.
void PressWheel(const Soil& soil, const WheelState& wheel, const SoilSurface& surface,
                SoilMemory* memory, int samples = 64);

}  // namespace simpartner::sim
