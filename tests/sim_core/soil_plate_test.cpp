// A body that is not a wheel on soil (soil_plate.h), against closed
// forms: where a vertical line enters a box, a sphere and a capsule; a
// flat box's footprint and Bekker's plate pressure on it; a sphere's
// footprint, the circle of a spherical cap; what the soil remembers; and
// Bekker's shear of a sliding plate.
#include <gtest/gtest.h>

#include <cmath>

#include "../../sim_core/src/soil_plate.h"
#include "soil_closed_forms.h"

namespace simpartner::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

const model::SoilParameters kDrySand = testing::WongEntry(1.1, 0.99, 1528.43, 1.04, 28);

PlateState Box(double lx, double ly, double lz, double y) {
  PlateState p;
  p.kind = model::GeometryKind::kBox;
  p.size = Eigen::Vector3d(lx, ly, lz);
  p.pose.translation() = Eigen::Vector3d(0, y, 0);
  return p;
}

TEST(SoilPlate, WhereAVerticalLineEntersEachShape) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  // A box 0.2 high centred at y = 0.09: its bottom at -0.01.
  EXPECT_NEAR(*PlateEntry(Box(0.2, 0.2, 0.4, 0.09), Eigen::Vector3d(0.05, 0, 0.1), up), -0.01,
              1e-12);
  EXPECT_FALSE(PlateEntry(Box(0.2, 0.2, 0.4, 0.09), Eigen::Vector3d(0.2, 0, 0), up));
  // Turned 45 degrees about z: its lowest edge at y = 0.09 - 0.1 sqrt(2).
  PlateState turned = Box(0.2, 0.2, 0.4, 0.09);
  turned.pose.linear() = Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(*PlateEntry(turned, Eigen::Vector3d(0, 0, 0), up), 0.09 - 0.1 * std::sqrt(2.0),
              1e-12);
  // A sphere of radius 0.1 at y = 0.09, 3 cm off its axis: the cap's surface.
  PlateState sphere;
  sphere.kind = model::GeometryKind::kSphere;
  sphere.size.x() = 0.1;
  sphere.pose.translation() = Eigen::Vector3d(0, 0.09, 0);
  EXPECT_NEAR(*PlateEntry(sphere, Eigen::Vector3d(0.03, 0, 0), up),
              0.09 - std::sqrt(0.01 - 0.0009), 1e-12);
  // A capsule lying along x (its z turned onto x), radius 0.05, cylinder
  // 0.4: under its cylinder and under one end's sphere.
  PlateState capsule;
  capsule.kind = model::GeometryKind::kCapsule;
  capsule.size = Eigen::Vector3d(0.05, 0.4, 0);
  capsule.pose.linear() = Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  capsule.pose.translation() = Eigen::Vector3d(0, 0.04, 0);
  EXPECT_NEAR(*PlateEntry(capsule, Eigen::Vector3d(0.1, 0, 0.0), up), -0.01, 1e-12);
  EXPECT_NEAR(*PlateEntry(capsule, Eigen::Vector3d(0.22, 0, 0.0), up),
              0.04 - std::sqrt(0.0025 - 0.0004), 1e-12);
}

// A 0.2 x 0.4 m box 1 cm into fresh sand: its whole underside presses,
// at Bekker's p(1 cm) for a 0.2 m wide plate.
TEST(SoilPlate, AFlatBoxPressesItsWholeFootprintAtBekkersPressure) {
  const Soil soil = Soil::From(kDrySand);
  SoilMemory memory;
  const PlateSoilForces f =
      PressPlateOnSoil(soil, Box(0.2, 0.1, 0.4, 0.04), SoilSurface{}, &memory);
  ASSERT_TRUE(f.touching);
  EXPECT_NEAR(f.area, 0.08, 1e-12);
  EXPECT_NEAR(f.width, 0.2, 1e-12);
  EXPECT_NEAR(f.length, 0.4, 1e-12);
  EXPECT_NEAR(f.sinkage, 0.01, 1e-12);
  const double p = testing::Bekker(kDrySand, 0.2, 0.01);
  EXPECT_NEAR(f.normal_force, p * 0.08, 1e-9 * p);
  EXPECT_NEAR(f.stiffness, 1.1 * p / 0.01 * 0.08, 1e-9 * p);
  EXPECT_LT(f.centroid.head<1>().norm() + std::abs(f.centroid.z()), 1e-12);
  // The soil remembers it: the same box 2 mm higher is on the unloading
  // line, pressing less than Bekker's curve would at 8 mm.
  const PlateSoilForces risen =
      PressPlateOnSoil(soil, Box(0.2, 0.1, 0.4, 0.042), SoilSurface{}, &memory);
  EXPECT_LT(risen.normal_force, testing::Bekker(kDrySand, 0.2, 0.008) * 0.08);
  EXPECT_GE(risen.normal_force, 0.0);
}

// A sphere of radius R sunk z: its footprint is the circle of radius
// sqrt(2 R z - z^2); the grid finds its area within a few per cent.
TEST(SoilPlate, ASpheresFootprintIsItsCapsCircle) {
  const Soil soil = Soil::From(kDrySand);
  SoilMemory memory;
  PlateState sphere;
  sphere.kind = model::GeometryKind::kSphere;
  sphere.size.x() = 0.1;
  sphere.pose.translation() = Eigen::Vector3d(0, 0.1 - 0.02, 0);
  const PlateSoilForces f = PressPlateOnSoil(soil, sphere, SoilSurface{}, &memory);
  ASSERT_TRUE(f.touching);
  const double a2 = 2 * 0.1 * 0.02 - 0.02 * 0.02;
  EXPECT_NEAR(f.area, kPi * a2, 0.05 * kPi * a2);
  EXPECT_NEAR(f.width, 2 * std::sqrt(a2), 0.15 * std::sqrt(a2));
  EXPECT_NEAR(f.sinkage, 0.02, 2e-3);
}

// Bekker's shear of a plate of length L: (A c + N tan phi) times
// 1 - (K / L)(1 - e^(-L / K)).
TEST(SoilPlate, ASlidingPlateIsHeldByBekkersShear) {
  const Soil soil = Soil::From(kDrySand);
  SoilMemory memory;
  const PlateSoilForces f =
      PressPlateOnSoil(soil, Box(0.2, 0.1, 0.4, 0.04), SoilSurface{}, &memory);
  const double K = kDrySand.shear_modulus, L = 0.4;
  const double full = 0.08 * 1.04e3 + f.normal_force * std::tan(28 * kPi / 180);
  EXPECT_NEAR(f.shear_strength, full * (1 - K / L * (1 - std::exp(-L / K))), 1e-9 * full);
}

TEST(SoilPlate, ABodyAboveTheSoilDoesNotTouchIt) {
  const Soil soil = Soil::From(kDrySand);
  SoilMemory memory;
  EXPECT_FALSE(PressPlateOnSoil(soil, Box(0.2, 0.1, 0.4, 0.06), SoilSurface{}, &memory).touching);
  EXPECT_EQ(memory.cells(), 0u);
}

}  // namespace
}  // namespace simpartner::sim
