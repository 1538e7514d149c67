// RayHeightfield (sim_core/src/ray_heightfield.h) against ODE's own ray test
// on the same heightfield: the same first hit for 2,000 rays from above, at
// every angle, over a bumpy field placed off the origin. ODE is the oracle
// here, an outside party: the test builds its field with ODE's own calls
// from the model, and reaches the sim's ODE engine only through engine.h.
#include <gtest/gtest.h>

#include <ode/ode.h>

#include <cmath>
#include <random>
#include <cstdio>
#include <memory>
#include <sstream>
#include <vector>

#include "../../sim_core/src/ray_heightfield.h"
#include "simpartner/sim/engine.h"
#include "test_worlds.h"

namespace simpartner::sim {
namespace {

std::string BumpyWorld() {
  std::ostringstream samples;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> height(-0.3, 0.4);
  for (int k = 0; k < 9 * 12; ++k) samples << height(random) << " ";
  return "<world name=\"Bumps\">" + testing::Vec("gravity", 0, -9.81, 0) +
         "<heightfield rows=\"9\" columns=\"12\"><width>6</width><depth>4</depth>"
         "<scale>1.5</scale><offset>0.2</offset><thickness>1</thickness>" +
         testing::Vec("position", 1.0, 0.5, -2.0) + "<samples>" + samples.str() +
         "</samples></heightfield></world>";
}

// ODE's distance along the ray to its nearest hit, or `range` when it
// misses. Asked for one contact, ODE gives the first it finds in its own
// order of cells, not the nearest: the old CastRay's error (see below).
double OdeRay(dGeomID field, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double range,
              int contacts = 256) {
  const dGeomID ray = dCreateRay(nullptr, range);
  dGeomRaySet(ray, o.x(), o.y(), o.z(), d.x(), d.y(), d.z());
  std::vector<dContactGeom> hits(static_cast<size_t>(contacts));
  const int n = dCollide(ray, field, contacts, hits.data(), sizeof(dContactGeom));
  dGeomDestroy(ray);
  double nearest = range;
  for (int k = 0; k < n; ++k) nearest = std::min(nearest, static_cast<double>(hits[k].depth));
  return nearest;
}

// The world's heightfield as ODE's own geom: its samples as given, ODE's
// field being y up with rows along z (the world's frame in these files).
class OdeField {
 public:
  explicit OdeField(const model::Heightfield& h) {
    dInitODE2(0);
    data_ = dGeomHeightfieldDataCreate();
    dGeomHeightfieldDataBuildDouble(data_, h.samples.data(), 1, h.width, h.depth, h.columns,
                                    h.rows, h.scale, h.offset, h.thickness, 0);
    geom_ = dCreateHeightfield(nullptr, data_, 1);
    dGeomSetPosition(geom_, h.position.x(), h.position.y(), h.position.z());
  }
  ~OdeField() {
    dGeomDestroy(geom_);
    dGeomHeightfieldDataDestroy(data_);
  }
  OdeField(const OdeField&) = delete;
  OdeField& operator=(const OdeField&) = delete;
  dGeomID geom() const { return geom_; }

 private:
  dHeightfieldDataID data_ = nullptr;
  dGeomID geom_ = nullptr;
};

TEST(RayHeightfield, FindsTheHitOdesRayTestFinds) {
  const model::World world = testing::LoadInline(BumpyWorld());
  ASSERT_TRUE(world.heightfield);
  const model::FlatModel flat = model::Flatten(world);
  Parameters params;  // engine=ode, the default
  const std::unique_ptr<PhysicsEngine> ode = MakeEngine(flat, params);
  const OdeField ode_field(*world.heightfield);
  const dGeomID field = ode_field.geom();
  const Eigen::Isometry3d pose = world.HeightfieldPose();
  ASSERT_TRUE(pose.linear().isIdentity(1e-12)) << "the field is y up, as ODE's";

  std::mt19937 random(11);
  std::uniform_real_distribution<double> x(-3.5, 5.5), z(-4.5, 0.5), y(1.2, 3.0), unit(-1, 1);
  int hits = 0, compared = 0, first_not_nearest = 0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d o(x(random), y(random), z(random));
    Eigen::Vector3d d(unit(random), -std::abs(unit(random)) - 0.05, unit(random));
    d.normalize();
    const double range = 8.0;
    const double ours = RayHeightfield(*world.heightfield, pose, o, d, range);
    const double theirs = OdeRay(field, o, d, range);
    ++compared;
    if (theirs < range) ++hits;
    if (OdeRay(field, o, d, range, 1) > theirs + 1e-9) ++first_not_nearest;
    ASSERT_NEAR(ours, theirs, 1e-9) << "ray " << k << " from " << o.transpose() << " along "
                                    << d.transpose();
  }
  EXPECT_GT(hits, 500) << "most rays should hit the field";
  EXPECT_LT(hits, compared) << "some should miss it";
  std::printf("%d of %d rays hit; ODE's first contact was not the nearest for %d\n", hits,
              compared, first_not_nearest);
  // Through the engine's interface too (the lidar's path).
  EXPECT_NEAR(ode->CastRay(Eigen::Vector3d(1.0, 3.0, -2.0), Eigen::Vector3d(0, -1, 0), 10.0, -1),
              OdeRay(field, Eigen::Vector3d(1.0, 3.0, -2.0), Eigen::Vector3d(0, -1, 0), 10.0),
              1e-9);
}

}  // namespace
}  // namespace simpartner::sim
