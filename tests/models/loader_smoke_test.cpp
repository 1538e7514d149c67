#include <gtest/gtest.h>

#include "simpartner/model/loader.h"

namespace simpartner::model {
namespace {

// The original's object form (SPEC section 3) loads unchanged.
TEST(LoaderSmoke, OriginalObjectFormLoads) {
  const std::string xml = R"(<?xml version="1.0"?>
<world name="FreeFall">
  <object type="Body" name="TestParticle">
    <mass>1</mass>
    <transformation>
      <T00>1</T00><T01>0</T01><T02>0</T02><T03>0</T03>
      <T10>0</T10><T11>1</T11><T12>0</T12><T13>10</T13>
      <T20>0</T20><T21>0</T21><T22>1</T22><T23>0</T23>
    </transformation>
    <translationalVelocity><vx>0</vx><vy>0</vy><vz>0</vz></translationalVelocity>
    <rotationalVelocity><omegax>0</omegax><omegay>0</omegay><omegaz>0</omegaz></rotationalVelocity>
  </object>
</world>
)";
  const WorldLoadResult result = ParseWorld(xml, "inline.xml");
  ASSERT_TRUE(result.world.has_value()) << result.diagnostics.Format();
  ASSERT_EQ(result.world->objects.size(), 1u);
  const Body& particle = result.world->objects[0];
  EXPECT_EQ(particle.name, "TestParticle");
  EXPECT_EQ(particle.geometry.kind, GeometryKind::kNone);
  EXPECT_DOUBLE_EQ(particle.mass, 1.0);
  EXPECT_DOUBLE_EQ(particle.pose.translation().y(), 10.0);
}

}  // namespace
}  // namespace simpartner::model
