// Wheel-soil mechanics against integrals computed here, apart from the
// sim's code: Simpson's rule on 20,000 intervals of the stresses Bekker,
// Janosi-Hanamoto and Wong-Reece give along a circular rim. The sim sums
// 64 points (midpoint rule); the tolerances below are that sum's error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "simpartner/sim/soil_mechanics.h"
#include "soil_closed_forms.h"

namespace simpartner::model {
// How gtest names a soil in a test's parameters.
inline void PrintTo(const SoilParameters& soil, std::ostream* out) {
  *out << "n " << soil.n << ", k_c " << soil.k_c << ", k_phi " << soil.k_phi;
}
}  // namespace simpartner::model

namespace simpartner::sim {
namespace {

using testing::Simpson;
using testing::WongEntry;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadius = 0.3, kWidth = 0.2;

const model::SoilParameters kDrySand = WongEntry(1.1, 0.99, 1528.43, 1.04, 28);
const model::SoilParameters kSandyLoam = WongEntry(0.7, 5.27, 1515.04, 1.72, 29);
const model::SoilParameters kClayeySoil = WongEntry(0.5, 13.19, 692.15, 4.14, 13);
const model::SoilParameters kSnow = WongEntry(1.6, 4.37, 196.72, 1.03, 19.7);

// Bekker's pressure [Pa] under this wheel's width.
double Bekker(const model::SoilParameters& p, double z) { return testing::Bekker(p, kWidth, z); }

WheelState WheelSunk(double sinkage) {
  WheelState wheel;
  wheel.radius = kRadius;
  wheel.width = kWidth;
  wheel.centre = Eigen::Vector3d(0, kRadius - sinkage, 0);
  return wheel;
}

// That wheel rolling toward +x at speed v, spinning at omega (its axle is
// +z), and moving along its axle at side_speed.
WheelState WheelRolling(double sinkage, double v, double omega, double side_speed = 0.0) {
  WheelState wheel = WheelSunk(sinkage);
  wheel.velocity = Eigen::Vector3d(v, 0, side_speed);
  wheel.angular_velocity = Eigen::Vector3d(0, 0, -omega);
  return wheel;
}

class StandingWheel : public ::testing::TestWithParam<model::SoilParameters> {};

// A wheel pressed straight down into untouched soil: both halves of the
// arc load, and the load is b r times the integral of p cos(theta).
TEST_P(StandingWheel, CarriesBekkersPressureOverItsArc) {
  const model::SoilParameters& p = GetParam();
  const Soil soil = Soil::From(p);
  for (const double z0 : {0.005, 0.02, 0.06}) {
    const double half = std::acos(1.0 - z0 / kRadius);
    const double expected = testing::StandingLoad(p, kRadius, kWidth, z0);
    const WheelSoilForces f = WheelOnSoil(soil, WheelSunk(z0), SoilSurface{}, SoilMemory{});
    ASSERT_TRUE(f.touching);
    EXPECT_NEAR(f.sinkage, z0, 1e-12);
    // Midpoint sums of (theta_1 - theta)^n near the arc's ends err by
    // about (1/64)^(n+1): 0.2 % at n = 0.5.
    EXPECT_NEAR(f.normal_force.y(), expected, 0.003 * expected) << "n " << p.n << ", z " << z0;
    // Symmetric: no horizontal force; still: no shear.
    EXPECT_NEAR(f.normal_force.x(), 0.0, 1e-9 * expected);
    EXPECT_NEAR(f.shear_force.norm(), 0.0, 1e-9 * expected);
    EXPECT_NEAR(f.contact_area, kWidth * kRadius * 2 * half, 1e-9);
    EXPECT_FALSE(f.stuck);
  }
}

std::string SoilName(const ::testing::TestParamInfo<model::SoilParameters>& info) {
  static const char* const kNames[] = {"dry_sand", "sandy_loam", "clayey_soil", "snow"};
  return kNames[info.index];
}

INSTANTIATE_TEST_SUITE_P(WongTable23, StandingWheel,
                         ::testing::Values(kDrySand, kSandyLoam, kClayeySoil, kSnow), SoilName);

TEST(SoilMemory, UnloadingFollowsItsLineAndReloadingReturnsToBekker) {
  const Soil soil = Soil::From(kDrySand);
  const double z_max = 0.03;
  const double p_max = Bekker(kDrySand, z_max);
  EXPECT_NEAR(PressureWithMemory(soil, z_max, z_max, kWidth), p_max, 1e-9 * p_max);
  // 1 mm of rebound takes k_u * 1 mm off.
  EXPECT_NEAR(PressureWithMemory(soil, z_max - 0.001, z_max, kWidth), p_max - 20000e3 * 0.001,
              1e-9 * p_max);
  // Far above: nothing (the rut's floor is at z_max - p_max / k_u).
  EXPECT_EQ(PressureWithMemory(soil, z_max - 1.1 * p_max / 20000e3, z_max, kWidth), 0.0);
  // Deeper than ever: Bekker again.
  EXPECT_NEAR(PressureWithMemory(soil, 0.04, z_max, kWidth), Bekker(kDrySand, 0.04), 1e-6);

  SoilMemory memory(0.002);
  memory.Press(0.0101, 0.0, 0.02, std::pow(0.02, soil.n));
  memory.Press(0.0119, 0.0, 0.01, std::pow(0.01, soil.n));  // the same 2 mm cell: the deeper stays
  EXPECT_EQ(memory.Deepest(0.0105, 0.0015), 0.02);
  EXPECT_EQ(memory.Deepest(0.0125, 0.0), 0.0);  // the next cell
  EXPECT_EQ(memory.cells(), 1u);
}

// Bounded: past its most cells the memory forgets those pressed longest
// ago, down to three quarters, and keeps the newest as they were.
TEST(SoilMemory, ForgetsThePressesLongestAgoPastItsBound) {
  SoilMemory memory(0.001);
  for (int k = 0; k < 100; ++k) memory.Press(0.001 * k + 0.0005, 0.0, 0.01 + 1e-4 * k, 1.0);
  EXPECT_EQ(memory.ForgetOldest(100), 0u);
  EXPECT_EQ(memory.ForgetOldest(80), 40u);
  EXPECT_EQ(memory.cells(), 60u);
  EXPECT_EQ(memory.Deepest(0.0395, 0.0), 0.0);  // the 40th press: forgotten
  EXPECT_DOUBLE_EQ(memory.Deepest(0.0405, 0.0), 0.01 + 1e-4 * 40);
  EXPECT_DOUBLE_EQ(memory.Deepest(0.0995, 0.0), 0.01 + 1e-4 * 99);
}

// Wong's unloading slope grows with the deepest sinkage, k_u = k_0 + A_u
// z_max (LETE sand: k_0 = 0, A_u = 503,000 kN/m^4).
TEST(SoilMemory, TheUnloadingSlopeGrowsWithTheDeepestSinkage) {
  model::SoilParameters p = kDrySand;
  p.unloading_stiffness = 0;
  p.unloading_growth = 503000;
  const Soil soil = Soil::From(p);
  for (const double z_max : {0.02, 0.05}) {
    const double rebound = 1e-4;
    const double lost = Bekker(p, z_max) - PressureWithMemory(soil, z_max - rebound, z_max, kWidth);
    EXPECT_NEAR(lost / rebound, 503000e3 * z_max, 1e-6 * 503000e3 * z_max) << z_max;
  }
}

// Unloading and loading never cross: heavy clay (n = 0.13) rises so
// steeply at first that a 10,000 kPa/m line from 2 cm would pass above
// Bekker's curve near the surface; the sim takes the curve's chord
// instead, so that the soil never pushes harder unloaded than loaded.
TEST(SoilMemory, UnloadingNeverCrossesLoading) {
  const model::SoilParameters p = testing::WongEntry(0.13, 12.70, 1555.95, 68.95, 34);
  model::SoilParameters line = p;
  line.unloading_stiffness = 10000;
  const Soil soil = Soil::From(line);
  const double z_max = 0.02;
  EXPECT_GT(Bekker(p, z_max) - 10000e3 * (z_max - 0.001), Bekker(p, 0.001));  // the plain line
  for (int k = 1; k < 200; ++k) {
    const double z = z_max * k / 200.0;
    EXPECT_LE(PressureWithMemory(soil, z, z_max, kWidth), Bekker(p, z) * (1 + 1e-12)) << z;
  }
}

// A wheel that has rolled at sinkage z0 up to here: the soil behind its
// lowest point was pressed to z0 and rebounds under the rear of the arc.
SoilMemory RolledTo(const Soil& soil, double z0, double cell) {
  SoilMemory memory(cell);
  for (double x = -0.4; x <= 1e-12; x += cell / 4) {
    WheelState wheel = WheelSunk(z0);
    wheel.centre.x() = x;
    PressWheel(soil, wheel, SoilSurface{}, &memory, 256);
  }
  return memory;
}

// Drawbar pull of a wheel rolling at slip i: b r times the integral of
// tau cos(theta) - sigma sin(theta) (Wong's eq. for a rigid wheel), sigma
// Bekker's at the front and on the unloading line behind, tau
// Janosi-Hanamoto's with Wong and Reece's shear displacement.
TEST(RollingWheel, DrawbarPullAgainstSlipIsWongsIntegral) {
  const model::SoilParameters& p = kDrySand;
  const Soil soil = Soil::From(p);
  const double z0 = 0.03, k_u = 20000e3;
  const SoilMemory memory = RolledTo(soil, z0, 0.0005);
  const double front = std::acos(1.0 - z0 / kRadius);
  const double rear = -std::acos(1.0 - Bekker(p, z0) / (k_u * kRadius));
  const double tan_phi = std::tan(p.friction_angle * kPi / 180);
  for (const double slip : {0.05, 0.2, 0.4, 0.6}) {
    const double omega = 2.0, v = (1.0 - slip) * kRadius * omega;
    auto sigma = [&](double t) {
      const double z = z0 - kRadius * (1.0 - std::cos(t));
      return t >= 0 ? Bekker(p, z) : std::max(0.0, Bekker(p, z0) - k_u * (z0 - z));
    };
    auto tau = [&](double t) {
      const double j = kRadius * ((front - t) - (1 - slip) * (std::sin(front) - std::sin(t)));
      return (p.cohesion * 1e3 + sigma(t) * tan_phi) * (1 - std::exp(-j / p.shear_modulus));
    };
    const double pull = kWidth * kRadius * Simpson([&](double t) {
      return tau(t) * std::cos(t) - sigma(t) * std::sin(t);
    }, rear, front);
    const double load = kWidth * kRadius * Simpson([&](double t) {
      return sigma(t) * std::cos(t) + tau(t) * std::sin(t);
    }, rear, front);
    const WheelState wheel = WheelRolling(z0, v, omega);
    const WheelSoilForces f = WheelOnSoil(soil, wheel, SoilSurface{}, memory, 256);
    EXPECT_NEAR(f.slip, slip, 1e-12);
    EXPECT_NEAR(f.theta_front, front, 0.01) << slip;
    EXPECT_NEAR(f.theta_rear, rear, 0.01) << slip;
    const double scale = std::abs(load);
    EXPECT_NEAR(f.Force().x(), pull, 0.01 * scale) << "slip " << slip;
    EXPECT_NEAR(f.Force().y(), load, 0.01 * scale) << "slip " << slip;
  }
}

// The sim's own path to a rolling wheel's ruts: 64 points a step, pressed
// as they answer (PressWheelOnSoil), 0.5 mm a step along the track. On
// snow, 162.5 mm deep, the rebound behind the lowest point is a sliver of
// 1.8 deg, narrower than the points' spacing (1.95 deg): the load is
// Wong's integral within 0.5 % only where the track keeps the lowest
// point's depth (without it, 2 % over) and the sliver's end is found
// inside its part of the arc.
TEST(RollingWheel, SixtyFourPointsCarryWongsLoadOnSnow) {
  const Soil soil = Soil::From(kSnow);
  const double z0 = 0.1625, slip = 0.2, omega = 2.0, v = (1 - slip) * kRadius * omega;
  SoilMemory memory;
  WheelSoilForces f;
  for (double x = -0.4; x <= 1e-12; x += 0.0005) {
    WheelState wheel = WheelRolling(z0, v, omega);
    wheel.centre.x() = x;
    f = PressWheelOnSoil(soil, wheel, SoilSurface{}, &memory);
  }
  const testing::RollingArc arc = testing::RollingStresses(kSnow, kRadius, kWidth, z0, slip, 0);
  const testing::RollingWheelForces expected = testing::RollingWheel(kSnow, kRadius, kWidth, z0, slip);
  // Found to 1/64 of the points' spacing (2 half / 64, half 1.095 rad).
  EXPECT_NEAR(f.theta_rear, arc.rear, 2 * 1.0947 / 64 / 64);
  EXPECT_NEAR(f.Force().y(), expected.load, 0.005 * expected.load);
  EXPECT_NEAR(f.Force().x(), expected.pull, 0.005 * expected.load);
}

// A wheel settling into clay, 2,000 steps down to Bekker's static sinkage
// and pressing as it goes: the load is Bekker's within 0.3 %. Each of its
// rim points reads the depth of its own memory cell; with 2 mm cells the
// depth a neighbouring point pressed there is off by the rim's slope times
// the cell, and the load came out 1.1 % short.
TEST(SoilMemory, AWheelSettlingIntoClayMeetsBekkersLoad) {
  const Soil soil = Soil::From(kClayeySoil);
  for (const double load : {490.5, 981.0}) {
    double lo = 0.0, hi = kRadius;
    for (int k = 0; k < 60; ++k)
      (testing::StandingLoad(kClayeySoil, kRadius, kWidth, 0.5 * (lo + hi)) < load ? lo : hi) =
          0.5 * (lo + hi);
    SoilMemory memory;
    WheelSoilForces f;
    for (int k = 1; k <= 2000; ++k)
      f = PressWheelOnSoil(soil, WheelSunk(lo * k / 2000.0), SoilSurface{}, &memory);
    EXPECT_NEAR(f.Force().y(), load, 0.003 * load);
    EXPECT_NEAR(f.Force().x(), 0.0, 1e-6 * load);
  }
}

// Multipass: a second pass over the same track sinks less. The first
// wheel sank z0 into untouched soil; the track it leaves is flat along its
// length with its floor at z0 - p(z0) / k_u (the rebound). A second wheel
// with the same load meets the stiff reloading line down to z0 and fresh
// soil (Bekker's curve) only below it, so it sinks into the track, but
// less than the first sank into untouched soil (as Wong reports for
// multi-pass: each pass adds less sinkage).
TEST(RollingWheel, ASecondPassInTheRutSinksLess) {
  for (const model::SoilParameters& p : {kDrySand, kSnow}) {
    const Soil soil = Soil::From(p);
    const double z0 = 0.04;
    WheelState first = WheelSunk(z0);
    first.velocity = Eigen::Vector3d(0.3, 0, 0);
    first.angular_velocity = Eigen::Vector3d(0, 0, -1.0);
    const SoilMemory rolled = RolledTo(soil, z0, 0.0005);
    const double load = WheelOnSoil(soil, first, SoilSurface{}, rolled, 256).Force().y();
    // The second wheel rolls the track the first left behind.
    auto second_load = [&](double z) {
      WheelState second = WheelSunk(z);
      second.centre.x() = -0.2;
      second.velocity = first.velocity;
      second.angular_velocity = first.angular_velocity;
      return WheelOnSoil(soil, second, SoilSurface{}, rolled, 256).Force().y();
    };
    double lo = 0.0, hi = 2 * z0;
    for (int k = 0; k < 60; ++k) ((second_load(0.5 * (lo + hi)) < load) ? lo : hi) = 0.5 * (lo + hi);
    // The track's floor under the second wheel, from what the soil remembers.
    const double pressed = rolled.Deepest(-0.2, 0.0);
    EXPECT_NEAR(pressed, z0, 2e-6);  // the arc's samples miss its lowest point by half a step
    const double floor = pressed - Bekker(p, pressed) / validate::UnloadingSlope(p, kWidth, pressed);
    const double into_track = hi - floor;
    EXPECT_GT(into_track, 0.0) << "n " << p.n;
    EXPECT_LT(into_track, 0.25 * z0) << "n " << p.n << ": the second pass sinks " << into_track
                                     << " m into the track, the first " << z0 << " m";
  }
}

// The slopes a contact solves with (ode_soil.h), against the derivatives
// of the closed forms above (central differences of their integrals).
TEST(SoilSlopes, StiffnessIsTheStandingLoadsSlope) {
  // Midpoint sums of p' ~ (theta_1 - theta)^(n-1) near the arc's ends err
  // by about (1/256)^n: 0.2 % at n = 1.1, 0.02 % at n = 1.6.
  for (const model::SoilParameters& p : {kDrySand, kSnow}) {
    const Soil soil = Soil::From(p);
    for (const double z0 : {0.01, 0.04}) {
      const double h = 1e-6;
      const double expected = (testing::StandingLoad(p, kRadius, kWidth, z0 + h) -
                               testing::StandingLoad(p, kRadius, kWidth, z0 - h)) /
                              (2 * h);
      WheelSoilSlopes slopes;
      WheelOnSoil(soil, WheelSunk(z0), SoilSurface{}, SoilMemory{}, 256, &slopes);
      EXPECT_NEAR(slopes.stiffness, expected, 0.005 * expected) << "n " << p.n << ", z " << z0;
    }
  }
}

TEST(SoilSlopes, ThrustSlopeIsThePullsSlopeAgainstSlipVelocity) {
  const model::SoilParameters& p = kDrySand;
  const Soil soil = Soil::From(p);
  const double z0 = 0.03, v = 0.4;
  const SoilMemory memory = RolledTo(soil, z0, 0.0005);
  for (const double omega : {1.5, 2.0, 3.0}) {
    // Only the shear depends on the spin: the pull's slope is the thrust's.
    // The slip velocity v - r omega falls by r d omega.
    const double d = 1e-4;
    auto pull = [&](double w) {
      return testing::RollingWheel(p, kRadius, kWidth, z0, 1.0 - v / (kRadius * w)).pull;
    };
    const double expected = (pull(omega + d) - pull(omega - d)) / (-2 * d * kRadius);
    const WheelState wheel = WheelRolling(z0, v, omega);
    WheelSoilSlopes slopes;
    WheelOnSoil(soil, wheel, SoilSurface{}, memory, 256, &slopes);
    EXPECT_LT(slopes.thrust_slope, 0.0);
    EXPECT_NEAR(slopes.thrust_slope, expected, 0.02 * std::abs(expected)) << "omega " << omega;
  }
}

// The sim presses the soil as it answers a wheel, in one pass: the same
// forces as answering first and pressing after, and the same ruts, also
// where several points of the arc share a cell of the memory (2 mm cells,
// a shallow arc).
TEST(SoilMemory, PressingWhileAnsweringChangesNeitherForcesNorRuts) {
  const Soil soil = Soil::From(kDrySand);
  for (const double z0 : {0.001, 0.03}) {
    SoilMemory answered_first = RolledTo(soil, 0.5 * z0, 0.002), pressed_while = answered_first;
    WheelState wheel = WheelRolling(z0, 0.3, 1.5);
    wheel.velocity.y() = -0.01;  // sinking too
    const WheelSoilForces expected = WheelOnSoil(soil, wheel, SoilSurface{}, answered_first);
    PressWheel(soil, wheel, SoilSurface{}, &answered_first);
    const WheelSoilForces got = PressWheelOnSoil(soil, wheel, SoilSurface{}, &pressed_while);
    EXPECT_EQ(got.Force(), expected.Force()) << "z " << z0;
    EXPECT_EQ(got.shear_torque, expected.shear_torque) << "z " << z0;
    ASSERT_EQ(pressed_while.cells(), answered_first.cells()) << "z " << z0;
    for (double x = -0.1; x < 0.1; x += 0.0005)
      EXPECT_EQ(pressed_while.Deepest(x, 0), answered_first.Deepest(x, 0)) << "x " << x;
  }
}

// Driven backward, a wheel is the mirror image of one driven forward: on
// untouched soil the same load and the opposite pull. (The shear once
// counted from the front edge either way: backward it pulled forward.)
TEST(RollingWheel, BackwardIsTheMirrorOfForward) {
  const Soil soil = Soil::From(kDrySand);
  for (const double slip : {0.1, 0.3}) {
    const double omega = 2.0, v = (1.0 - slip) * kRadius * omega;
    const WheelState forward = WheelRolling(0.03, v, omega);
    const WheelState backward = WheelRolling(0.03, -v, -omega);
    const WheelSoilForces f = WheelOnSoil(soil, forward, SoilSurface{}, SoilMemory{});
    const WheelSoilForces b = WheelOnSoil(soil, backward, SoilSurface{}, SoilMemory{});
    EXPECT_GT(f.Force().x(), 10.0) << "slip " << slip;
    EXPECT_NEAR(b.Force().x(), -f.Force().x(), 1e-9 * f.Force().norm()) << "slip " << slip;
    EXPECT_NEAR(b.Force().y(), f.Force().y(), 1e-9 * f.Force().norm()) << "slip " << slip;
    EXPECT_NEAR(b.shear_torque, -f.shear_torque, 1e-9 * std::abs(f.shear_torque));
    EXPECT_NEAR(b.slip, f.slip, 1e-12);
  }
}

// A wheel slipping sideways at slip angle alpha, rolling steadily in its
// own track (the rear of its arc on the unloading line, as Wong's): its
// side force and pull against Wong's combined-slip integral (the rim
// point's displacement along the rim and across it, one Janosi-Hanamoto
// law of the whole): a side force against the side speed, growing with
// alpha, and the pull less than without it.
TEST(RollingWheel, SideSlipGivesWongsSideForceAndTakesFromThePull) {
  const model::SoilParameters& p = kDrySand;
  const Soil soil = Soil::From(p);
  const double z0 = 0.03, slip = 0.2, omega = 2.0, v = (1.0 - slip) * kRadius * omega;
  const SoilMemory rolled = RolledTo(soil, z0, 0.0005);  // its own track behind it, as Wong's wheel
  double last_side = 0;
  for (const double alpha_deg : {2.0, 5.0, 15.0}) {
    const double tan_alpha = std::tan(alpha_deg * kPi / 180);
    const validate::SideSlipForces expected =
        validate::RollingWheelSideSlip(p, kRadius, kWidth, z0, slip, tan_alpha);
    const WheelState wheel = WheelRolling(z0, v, omega, v * tan_alpha);
    const WheelSoilForces f = WheelOnSoil(soil, wheel, SoilSurface{}, rolled, 256);
    const double load = f.Force().y();
    std::printf("alpha %.0f deg: side force %.2f N (Wong %.2f), pull %.2f N (Wong %.2f)\n",
                alpha_deg, f.side_force, expected.side, f.Force().x(), expected.pull);
    EXPECT_NEAR(f.side_speed, v * tan_alpha, 1e-12);
    EXPECT_LT(f.side_force, 0.0) << alpha_deg;
    EXPECT_NEAR(f.side_force, expected.side, 0.005 * load) << "alpha " << alpha_deg;
    EXPECT_NEAR(f.Force().z(), f.side_force, 1e-9 * load);
    EXPECT_NEAR(f.Force().x(), expected.pull, 0.005 * load) << "alpha " << alpha_deg;
    EXPECT_LT(f.side_force, last_side);
    last_side = f.side_force;
  }
  const WheelState straight = WheelRolling(z0, v, omega);
  const WheelSoilForces f0 = WheelOnSoil(soil, straight, SoilSurface{}, rolled, 256);
  EXPECT_EQ(f0.side_force, 0.0);
  const WheelState sideways = WheelRolling(z0, v, omega, v * std::tan(15 * kPi / 180));
  EXPECT_LT(WheelOnSoil(soil, sideways, SoilSurface{}, rolled, 256).Force().x(),
            f0.Force().x());
}

// The side force's slope against the side speed, which the contact's
// second row is linearized with, against the derivative of Wong's
// combined-slip integral (central differences in the slip angle).
TEST(SoilSlopes, SideSlopeIsTheSideForcesSlopeAgainstSideSpeed) {
  const model::SoilParameters& p = kDrySand;
  const Soil soil = Soil::From(p);
  const double z0 = 0.03, slip = 0.2, omega = 2.0, v = (1.0 - slip) * kRadius * omega;
  const SoilMemory rolled = RolledTo(soil, z0, 0.0005);
  for (const double side_speed : {0.0, 0.02, 0.1}) {
    const double d = 1e-4;
    auto side = [&](double v_y) {
      return validate::RollingWheelSideSlip(p, kRadius, kWidth, z0, slip, v_y / v).side;
    };
    const double expected = (side(side_speed + d) - side(side_speed - d)) / (2 * d);
    const WheelState wheel = WheelRolling(z0, v, omega, side_speed);
    WheelSoilSlopes slopes;
    WheelOnSoil(soil, wheel, SoilSurface{}, rolled, 256, &slopes);
    EXPECT_LT(slopes.side_slope, 0.0);
    EXPECT_NEAR(slopes.side_slope, expected, 0.02 * std::abs(expected)) << "v_y " << side_speed;
  }
}

TEST(RollingWheel, AWheelSunkPastItsAxleIsStuckNotNaN) {
  const Soil soil = Soil::From(kSnow);
  const WheelSoilForces f = WheelOnSoil(soil, WheelSunk(1.5 * kRadius), SoilSurface{}, SoilMemory{});
  EXPECT_TRUE(f.stuck);
  EXPECT_TRUE(f.Force().allFinite());
  EXPECT_NEAR(f.theta_front, kPi / 2, 0.03);
}

}  // namespace
}  // namespace simpartner::sim
