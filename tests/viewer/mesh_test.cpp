// The meshes of every geometry kind, the heightfield and the plane, built
// without GL: their extent matches the sizes, normals are unit and point
// outwards, and the heightfield sits where the sim puts it.
#include <gtest/gtest.h>

#include <cmath>

#include "simpartner/viewer/mesh.h"

namespace simpartner::viewer {
namespace {

Eigen::AlignedBox3f Bounds(const Mesh& m) {
  Eigen::AlignedBox3f box;
  for (const Eigen::Vector3f& p : m.positions) box.extend(p);
  return box;
}

// Every triangle's winding agrees with its vertex normals and, for a
// convex shape around the origin, they point away from the centre.
void ExpectOutwardAndUnit(const Mesh& m, const char* what) {
  ASSERT_EQ(m.positions.size(), m.normals.size()) << what;
  ASSERT_EQ(m.positions.size() % 3, 0u) << what;
  for (size_t t = 0; t < m.positions.size(); t += 3) {
    const Eigen::Vector3f a = m.positions[t], b = m.positions[t + 1], c = m.positions[t + 2];
    const Eigen::Vector3f face = (b - a).cross(c - a);
    ASSERT_GT(face.norm(), 0) << what << ": degenerate triangle " << t / 3;
    const Eigen::Vector3f centre = (a + b + c) / 3;
    EXPECT_GT(face.dot(centre), 0) << what << ": triangle " << t / 3 << " faces inwards";
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(m.normals[t + k].norm(), 1, 1e-5) << what;
      EXPECT_GT(m.normals[t + k].dot(face), 0) << what << ": normal against winding";
    }
  }
}

TEST(MeshTest, BoxSpansItsSizeWithTwelveOutwardTriangles) {
  const Mesh m = BoxMesh(Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(m.triangles(), 12u);
  const Eigen::AlignedBox3f b = Bounds(m);
  EXPECT_TRUE(b.min().isApprox(Eigen::Vector3f(-0.5f, -1, -1.5f)));
  EXPECT_TRUE(b.max().isApprox(Eigen::Vector3f(0.5f, 1, 1.5f)));
  ExpectOutwardAndUnit(m, "box");
}

TEST(MeshTest, SphereVerticesLieOnItsRadius) {
  const Mesh m = SphereMesh(0.7);
  for (const Eigen::Vector3f& p : m.positions) EXPECT_NEAR(p.norm(), 0.7f, 1e-5);
  ExpectOutwardAndUnit(m, "sphere");
  EXPECT_NEAR(Bounds(m).max().z(), 0.7f, 1e-5);
}

TEST(MeshTest, CylinderAndCapsuleRunAlongZ) {
  const Mesh cylinder = CylinderMesh(0.3, 2.0);
  EXPECT_NEAR(Bounds(cylinder).max().z(), 1.0f, 1e-6);
  EXPECT_NEAR(Bounds(cylinder).max().x(), 0.3f, 1e-6);
  ExpectOutwardAndUnit(cylinder, "cylinder");
  const Mesh capsule = CapsuleMesh(0.3, 2.0);
  // The caps add a radius at each end.
  EXPECT_NEAR(Bounds(capsule).max().z(), 1.3f, 1e-5);
  EXPECT_NEAR(Bounds(capsule).min().z(), -1.3f, 1e-5);
  for (const Eigen::Vector3f& p : capsule.positions) {
    const float axis_z = std::clamp(p.z(), -1.0f, 1.0f);
    EXPECT_NEAR((p - Eigen::Vector3f(0, 0, axis_z)).norm(), 0.3f, 1e-5);
  }
  ExpectOutwardAndUnit(capsule, "capsule");
}

TEST(MeshTest, GeometryKindsMapToTheirMeshes) {
  geometry_t g{};
  g.kind = geometry_t::KIND_NONE;  // a point mass: a marker, so it can be seen
  EXPECT_EQ(GeometryMesh(g).triangles(), 8u);
  ExpectOutwardAndUnit(GeometryMesh(g), "point mass");
  EXPECT_NEAR(Bounds(GeometryMesh(g)).max().y(), 0.05f, 1e-6);
  g.kind = geometry_t::KIND_SPHERE;
  g.size[0] = 2;
  EXPECT_NEAR(Bounds(GeometryMesh(g)).max().x(), 2, 1e-5);
  g.kind = geometry_t::KIND_CYLINDER;
  g.size[0] = 0.5;
  g.size[1] = 4;
  EXPECT_NEAR(Bounds(GeometryMesh(g)).max().z(), 2, 1e-5);
}

heightfield_t Field() {
  heightfield_t f{};
  f.present = true;
  f.rows = 3;     // along z
  f.columns = 4;  // along x
  f.width = 6;    // x -3..3
  f.depth = 2;    // z -1..1
  f.scale = 0.5;
  f.offset = 0.1;
  f.thickness = 1;
  f.position[0] = 10;
  f.position[1] = -1;
  f.samples = {0, 0, 0, 0,   //
               0, 4, 0, 0,   // a peak at row 1, column 1
               0, 0, 0, 0};
  f.num_samples = 12;
  return f;
}

// A heightfield's colours: dark in the hollows, light on the tops.
const Eigen::Vector3f kLow(0.2f, 0.2f, 0.2f), kHigh(0.8f, 0.8f, 0.8f);

TEST(MeshTest, HeightfieldSamplesSitWhereTheSimPutsThem) {
  const heightfield_t f = Field();
  const Mesh m = HeightfieldMesh(f, Eigen::Vector3d::UnitY(), kLow, kHigh);
  EXPECT_EQ(m.triangles(), 2u * 2 * 3);
  EXPECT_EQ(m.colors.size(), m.positions.size());
  // Sample (row 1, column 1): x = -3 + 6 * 1/3 = -1, z = -1 + 2 * 1/2 = 0,
  // height 0.5 * 4 + 0.1 = 2.1, then moved by (10, -1, 0).
  const Eigen::Vector3f peak(9, 1.1f, 0);
  bool found = false;
  for (const Eigen::Vector3f& p : m.positions) found |= (p - peak).norm() < 1e-5;
  EXPECT_TRUE(found);
  const Eigen::AlignedBox3f b = Bounds(m);
  EXPECT_TRUE(b.min().isApprox(Eigen::Vector3f(7, -0.9f, -1), 1e-5));
  EXPECT_TRUE(b.max().isApprox(Eigen::Vector3f(13, 1.1f, 1), 1e-5));
  // Seen from above: every face and normal points up.
  for (size_t t = 0; t < m.triangles(); ++t) {
    const Eigen::Vector3f a = m.positions[m.Corner(t, 0)], b = m.positions[m.Corner(t, 1)],
                          c = m.positions[m.Corner(t, 2)];
    EXPECT_GT((b - a).cross(c - a).y(), 0);
    EXPECT_GT(m.normals[m.Corner(t, 0)].y(), 0);
  }
  // Neighbouring triangles share their vertices: one per sample.
  EXPECT_EQ(m.positions.size(), 12u);
  // The peak is lighter than the flat ground.
  size_t peak_index = 0, flat_index = 0;
  for (size_t i = 0; i < m.positions.size(); ++i) {
    if ((m.positions[i] - peak).norm() < 1e-5) peak_index = i;
    if ((m.positions[i] - Eigen::Vector3f(7, -0.9f, -1)).norm() < 1e-5) flat_index = i;
  }
  EXPECT_GT(m.colors[peak_index].sum(), m.colors[flat_index].sum());
}

TEST(MeshTest, HeightfieldTurnsWithUp) {
  heightfield_t f = Field();
  f.position[0] = f.position[1] = 0;
  const Mesh m = HeightfieldMesh(f, Eigen::Vector3d::UnitZ(), kLow, kHigh);
  // Heights now run along z.
  float top = -1e9f;
  for (const Eigen::Vector3f& p : m.positions) top = std::max(top, p.z());
  EXPECT_NEAR(top, 2.1f, 1e-5);
}

TEST(MeshTest, HeightfieldGridFollowsWholeMetresAndSkipsFlatStretches) {
  heightfield_t f = Field();  // columns at x = 7, 9, 11, 13; rows at z = -1, 0, 1
  const Lines grid = HeightfieldGrid(f, Eigen::Vector3d::UnitY(), 1.0, 0.01, 0.001);
  // 7, 9, 11, 13 are each the column nearest a whole metre and the rows lie
  // on whole metres. Flat lines are one segment; the line through the peak
  // (column 1, row 1) keeps every sample: 2 + 1 + 1 + 1 column segments,
  // 1 + 3 + 1 row segments.
  EXPECT_EQ(grid.segments(), 5u + 5u);
  bool through_peak = false;
  for (const Eigen::Vector3f& p : grid.positions) {
    EXPECT_GE(p.y(), -0.9f + 0.01f - 1e-5);
    through_peak |= (p - Eigen::Vector3f(9, 1.11f, 0)).norm() < 1e-5;
  }
  EXPECT_TRUE(through_peak);
  // Without simplification every sample is a vertex: 4 lines of 2 and 3
  // lines of 3 segments.
  EXPECT_EQ(HeightfieldGrid(f, Eigen::Vector3d::UnitY(), 1.0, 0.01, -1).segments(), 4u * 2 + 3u * 3);
}

TEST(MeshTest, PlaneSquareLiesOnThePlaneFacingItsNormal) {
  const double plane[4] = {0, 2, 0, 1};  // y = 0.5
  const Mesh m = PlaneMesh(plane, Eigen::Vector3d(3, 7, -2), 10);
  ASSERT_EQ(m.triangles(), 2u);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(m.positions[i].y(), 0.5f, 1e-6);
    EXPECT_NEAR(m.normals[i].y(), 1.0f, 1e-6);
  }
  const Eigen::AlignedBox3f b = Bounds(m);
  EXPECT_NEAR(b.center().x(), 3, 1e-5);
  EXPECT_NEAR(b.center().z(), -2, 1e-5);
  EXPECT_NEAR(b.sizes().x(), 20, 1e-4);
  const Lines grid = PlaneGrid(plane, Eigen::Vector3d(0.5, 0, 0), 2, 1);
  // Across x: whole metres within 0.5 +- 2 (-1, 0, 1, 2); across z:
  // within 0 +- 2 (-2 .. 2).
  EXPECT_EQ(grid.segments(), 4u + 5u);
  for (const Eigen::Vector3f& p : grid.positions) EXPECT_NEAR(p.y(), 0.5f, 1e-6);
}

}  // namespace
}  // namespace simpartner::viewer
