// Triangle meshes of the geometry kinds, built on the CPU (no GL) so that
// their shape is unit tested; the renderer compiles them into display lists.
// Frames follow the sim (ODE): shapes are centred on the body frame origin,
// cylinders and capsules have their axis along body z.
#pragma once

#include <Eigen/Geometry>

#include <vector>

#include "simpartner/geometry_t.hpp"
#include "simpartner/heightfield_t.hpp"

namespace simpartner::viewer {

// Triangles with per-vertex normals and, optionally, per-vertex colours
// (RGB 0..1). Without indices every 3 vertices are a triangle; with them
// (large meshes: vertices shared by up to 6 triangles are lit once) every
// 3 indices are.
struct Mesh {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Eigen::Vector3f> colors;  // empty: one colour for the mesh
  std::vector<uint32_t> indices;        // empty: not indexed
  size_t triangles() const { return (indices.empty() ? positions.size() : indices.size()) / 3; }
  // Vertex k (0..2) of triangle t.
  size_t Corner(size_t t, int k) const {
    return indices.empty() ? 3 * t + k : indices[3 * t + k];
  }
  void Append(const Mesh& other);  // both not indexed
};

// Line segments (2 vertices each).
struct Lines {
  std::vector<Eigen::Vector3f> positions;
  size_t segments() const { return positions.size() / 2; }
};

Mesh BoxMesh(const Eigen::Vector3d& size);
// `slices` around the axis, `stacks` from pole to pole.
Mesh SphereMesh(double radius, int slices = 24, int stacks = 12);
// Closed cylinder, axis z, centred.
Mesh CylinderMesh(double radius, double length, int slices = 24);
// Cylinder of `length` with hemispherical caps (total length + 2 radius).
Mesh CapsuleMesh(double radius, double length, int slices = 24, int stacks = 12);
// A small octahedron (corners `radius` from the centre) marking a point mass.
Mesh PointMassMesh(double radius = 0.05);
// The mesh of one body's geometry; a point mass (KIND_NONE) gets the marker.
Mesh GeometryMesh(const geometry_t& geometry);

// The world-frame surface of a heightfield (as the sim builds it: columns
// along x over [-width/2, width/2], rows along z over [-depth/2, depth/2],
// height = scale * sample + offset, turned so that its y follows `up`, then
// moved to `position`), with smooth normals and colours by height, from
// `low` in its hollows to `high` on its tops (RGB 0..1).
Mesh HeightfieldMesh(const heightfield_t& field, const Eigen::Vector3d& up,
                     const Eigen::Vector3f& low, const Eigen::Vector3f& high);
// Height (along up, before the position offset) of sample (row, column).
double HeightfieldSample(const heightfield_t& field, int row, int column);
// The field's frame in the world: its y along `up`, its origin at its
// position (as HeightfieldMesh places it).
Eigen::Isometry3d HeightfieldPose(const heightfield_t& field, const Eigen::Vector3d& up);
// Height (as HeightfieldSample) of the surface HeightfieldMesh draws at
// (x, z) of the field's frame: on the triangle there, clamped at the
// field's border.
double HeightfieldSurface(const heightfield_t& field, double x, double z);
// Grid lines on the heightfield surface along the sample rows and columns
// that lie nearest to every `spacing` metres, lifted by `lift` along up.
// Samples where a line stays within `tolerance` of a straight chord are
// left out (Douglas-Peucker), so flat stretches cost one segment.
Lines HeightfieldGrid(const heightfield_t& field, const Eigen::Vector3d& up, double spacing,
                      double lift, double tolerance);

// A square of half-size `half` on the plane a*x + b*y + c*z = d, centred on
// the point of the plane nearest to `around`; normal (a, b, c) normalised.
Mesh PlaneMesh(const double plane[4], const Eigen::Vector3d& around, double half);
// Grid lines every `spacing` m on that plane (aligned to whole multiples of
// spacing in the plane's own axes), `half` m around `around`.
Lines PlaneGrid(const double plane[4], const Eigen::Vector3d& around, double half, double spacing);

}  // namespace simpartner::viewer
