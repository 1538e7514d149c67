#include "simpartner/viewer/mesh.h"

#include <algorithm>
#include <cmath>

namespace simpartner::viewer {
namespace {

using V3 = Eigen::Vector3f;

void Triangle(Mesh* m, const V3& a, const V3& b, const V3& c, const V3& na, const V3& nb,
              const V3& nc) {
  m->positions.insert(m->positions.end(), {a, b, c});
  m->normals.insert(m->normals.end(), {na, nb, nc});
}

void FlatTriangle(Mesh* m, const V3& a, const V3& b, const V3& c) {
  const V3 n = (b - a).cross(c - a).normalized();
  Triangle(m, a, b, c, n, n, n);
}

// Quad a b c d counter-clockwise seen from outside.
void FlatQuad(Mesh* m, const V3& a, const V3& b, const V3& c, const V3& d) {
  FlatTriangle(m, a, b, c);
  FlatTriangle(m, a, c, d);
}

// Rotation taking y to `up` (as the sim turns the heightfield).
Eigen::Matrix3d UpRotation(const Eigen::Vector3d& up) {
  return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitY(), up.normalized())
      .toRotationMatrix();
}

// Orthonormal in-plane axes (u, v) and unit normal n of a*x + b*y + c*z = d.
struct PlaneFrame {
  Eigen::Vector3d n, u, v;
  double offset;  // d / |(a, b, c)|: the plane is n . x = offset
};

PlaneFrame MakePlaneFrame(const double plane[4]) {
  PlaneFrame f;
  const Eigen::Vector3d raw(plane[0], plane[1], plane[2]);
  f.n = raw.normalized();
  f.offset = plane[3] / raw.norm();
  const Eigen::Vector3d reference =
      std::abs(f.n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  f.u = (reference - reference.dot(f.n) * f.n).normalized();
  f.v = f.n.cross(f.u);
  return f;
}

}  // namespace

void Mesh::Append(const Mesh& other) {
  positions.insert(positions.end(), other.positions.begin(), other.positions.end());
  normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  colors.insert(colors.end(), other.colors.begin(), other.colors.end());
}

Mesh BoxMesh(const Eigen::Vector3d& size) {
  const V3 h = (size / 2).cast<float>();
  auto p = [&](int sx, int sy, int sz) { return V3(sx * h.x(), sy * h.y(), sz * h.z()); };
  Mesh m;
  FlatQuad(&m, p(1, -1, -1), p(1, 1, -1), p(1, 1, 1), p(1, -1, 1));      // +x
  FlatQuad(&m, p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1), p(-1, -1, -1));  // -x
  FlatQuad(&m, p(-1, 1, -1), p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1));      // +y
  FlatQuad(&m, p(-1, -1, 1), p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1));  // -y
  FlatQuad(&m, p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1));      // +z
  FlatQuad(&m, p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1));  // -z
  return m;
}

namespace {

// Part of a sphere of radius r centred at (0, 0, z_shift): stacks from polar
// angle theta0 to theta1 (0 = +z pole).
void SphereBand(Mesh* m, double r, double z_shift, double theta0, double theta1, int slices,
                int stacks) {
  auto unit = [](double theta, double phi) {
    return V3(static_cast<float>(std::sin(theta) * std::cos(phi)),
              static_cast<float>(std::sin(theta) * std::sin(phi)),
              static_cast<float>(std::cos(theta)));
  };
  const V3 shift(0, 0, static_cast<float>(z_shift));
  const float rf = static_cast<float>(r);
  for (int i = 0; i < stacks; ++i) {
    const double t0 = theta0 + (theta1 - theta0) * i / stacks;
    const double t1 = theta0 + (theta1 - theta0) * (i + 1) / stacks;
    for (int j = 0; j < slices; ++j) {
      const double p0 = 2 * M_PI * j / slices;
      const double p1 = 2 * M_PI * (j + 1) / slices;
      const V3 a = unit(t0, p0), b = unit(t1, p0), c = unit(t1, p1), d = unit(t0, p1);
      // Skip the degenerate triangle at a pole.
      if (std::sin(t0) > 1e-9) Triangle(m, rf * a + shift, rf * b + shift, rf * d + shift, a, b, d);
      if (std::sin(t1) > 1e-9) Triangle(m, rf * b + shift, rf * c + shift, rf * d + shift, b, c, d);
    }
  }
}

void CylinderSide(Mesh* m, double r, double length, int slices) {
  const float h = static_cast<float>(length / 2);
  const float rf = static_cast<float>(r);
  for (int j = 0; j < slices; ++j) {
    const double p0 = 2 * M_PI * j / slices, p1 = 2 * M_PI * (j + 1) / slices;
    const V3 n0(static_cast<float>(std::cos(p0)), static_cast<float>(std::sin(p0)), 0);
    const V3 n1(static_cast<float>(std::cos(p1)), static_cast<float>(std::sin(p1)), 0);
    const V3 a = rf * n0 + V3(0, 0, -h), b = rf * n1 + V3(0, 0, -h);
    const V3 c = rf * n1 + V3(0, 0, h), d = rf * n0 + V3(0, 0, h);
    Triangle(m, a, b, c, n0, n1, n1);
    Triangle(m, a, c, d, n0, n1, n0);
  }
}

}  // namespace

Mesh SphereMesh(double radius, int slices, int stacks) {
  Mesh m;
  SphereBand(&m, radius, 0, 0, M_PI, slices, stacks);
  return m;
}

Mesh CylinderMesh(double radius, double length, int slices) {
  Mesh m;
  CylinderSide(&m, radius, length, slices);
  const float h = static_cast<float>(length / 2);
  const float rf = static_cast<float>(radius);
  for (int j = 0; j < slices; ++j) {
    const double p0 = 2 * M_PI * j / slices, p1 = 2 * M_PI * (j + 1) / slices;
    const V3 e0(rf * static_cast<float>(std::cos(p0)), rf * static_cast<float>(std::sin(p0)), 0);
    const V3 e1(rf * static_cast<float>(std::cos(p1)), rf * static_cast<float>(std::sin(p1)), 0);
    const V3 top(0, 0, h), bottom(0, 0, -h);
    FlatTriangle(&m, top, e0 + top, e1 + top);
    FlatTriangle(&m, bottom, e1 + bottom, e0 + bottom);
  }
  return m;
}

Mesh CapsuleMesh(double radius, double length, int slices, int stacks) {
  Mesh m;
  if (length > 0) CylinderSide(&m, radius, length, slices);
  SphereBand(&m, radius, length / 2, 0, M_PI / 2, slices, stacks / 2);
  SphereBand(&m, radius, -length / 2, M_PI / 2, M_PI, slices, stacks / 2);
  return m;
}

Mesh GeometryMesh(const geometry_t& g) {
  switch (g.kind) {
    case geometry_t::KIND_BOX: return BoxMesh(Eigen::Vector3d(g.size[0], g.size[1], g.size[2]));
    case geometry_t::KIND_SPHERE: return SphereMesh(g.size[0]);
    case geometry_t::KIND_CYLINDER: return CylinderMesh(g.size[0], g.size[1]);
    case geometry_t::KIND_CAPSULE: return CapsuleMesh(g.size[0], g.size[1]);
    default: return Mesh();
  }
}

double HeightfieldSample(const heightfield_t& f, int row, int column) {
  return f.scale * f.samples[static_cast<size_t>(row) * f.columns + column] + f.offset;
}

namespace {

// Local (y-up) position of sample (row, column).
Eigen::Vector3d FieldPoint(const heightfield_t& f, int row, int column) {
  return Eigen::Vector3d(-f.width / 2 + f.width * column / (f.columns - 1),
                         HeightfieldSample(f, row, column),
                         -f.depth / 2 + f.depth * row / (f.rows - 1));
}

}  // namespace

Mesh HeightfieldMesh(const heightfield_t& f, const Eigen::Vector3d& up) {
  Mesh m;
  if (!f.present || f.rows < 2 || f.columns < 2) return m;
  const Eigen::Matrix3d turn = UpRotation(up);
  const Eigen::Vector3d at(f.position[0], f.position[1], f.position[2]);
  double lo = HeightfieldSample(f, 0, 0), hi = lo;
  for (int r = 0; r < f.rows; ++r)
    for (int c = 0; c < f.columns; ++c) {
      lo = std::min(lo, HeightfieldSample(f, r, c));
      hi = std::max(hi, HeightfieldSample(f, r, c));
    }
  // Smooth normals from central differences, in the local frame.
  auto local_normal = [&](int r, int c) -> Eigen::Vector3d {
    const int c0 = std::max(c - 1, 0), c1 = std::min(c + 1, f.columns - 1);
    const int r0 = std::max(r - 1, 0), r1 = std::min(r + 1, f.rows - 1);
    const Eigen::Vector3d dx = FieldPoint(f, r, c1) - FieldPoint(f, r, c0);
    const Eigen::Vector3d dz = FieldPoint(f, r1, c) - FieldPoint(f, r0, c);
    return dz.cross(dx).normalized();  // +y for a flat field
  };
  // Snow: bluish grey in the hollows to white on the tops.
  auto color = [&](double height) {
    const float t = hi > lo ? static_cast<float>((height - lo) / (hi - lo)) : 1.0f;
    return V3(0.66f + 0.28f * t, 0.72f + 0.24f * t, 0.80f + 0.17f * t);
  };
  auto vertex = [&](int r, int c) {
    // Eigen expressions must become values here, not outlive their operands.
    return std::make_tuple(V3((turn * FieldPoint(f, r, c) + at).cast<float>()),
                           V3((turn * local_normal(r, c)).cast<float>()),
                           color(HeightfieldSample(f, r, c)));
  };
  m.positions.reserve(static_cast<size_t>(f.rows - 1) * (f.columns - 1) * 6);
  for (int r = 0; r + 1 < f.rows; ++r)
    for (int c = 0; c + 1 < f.columns; ++c) {
      const auto [p00, n00, k00] = vertex(r, c);
      const auto [p01, n01, k01] = vertex(r, c + 1);
      const auto [p10, n10, k10] = vertex(r + 1, c);
      const auto [p11, n11, k11] = vertex(r + 1, c + 1);
      // Counter-clockwise seen from above (+y): (r, c) -> (r + 1, c) -> (r, c + 1).
      Triangle(&m, p00, p10, p01, n00, n10, n01);
      Triangle(&m, p01, p10, p11, n01, n10, n11);
      m.colors.insert(m.colors.end(), {k00, k10, k01, k01, k10, k11});
    }
  return m;
}

Lines HeightfieldGrid(const heightfield_t& f, const Eigen::Vector3d& up, double spacing,
                      double lift) {
  Lines lines;
  if (!f.present || f.rows < 2 || f.columns < 2 || spacing <= 0) return lines;
  const Eigen::Matrix3d turn = UpRotation(up);
  const Eigen::Vector3d at(f.position[0], f.position[1], f.position[2]);
  const Eigen::Vector3d lift_local(0, lift, 0);
  auto world = [&](int r, int c) -> V3 {
    return (turn * (FieldPoint(f, r, c) + lift_local) + at).cast<float>();
  };
  // Sample indices nearest to each multiple of spacing (in world-ish
  // coordinates along that axis, so lines of neighbouring fields agree).
  auto lines_at = [&](int count, double extent, double centre) {
    std::vector<int> picked;
    const double step = extent / (count - 1);
    const double first = centre - extent / 2;
    for (double g = std::ceil(first / spacing) * spacing; g <= first + extent + 1e-9; g += spacing) {
      const int index = static_cast<int>(std::lround((g - first) / step));
      if (index >= 0 && index < count && (picked.empty() || picked.back() != index))
        picked.push_back(index);
    }
    return picked;
  };
  for (int c : lines_at(f.columns, f.width, f.position[0]))
    for (int r = 0; r + 1 < f.rows; ++r)
      lines.positions.insert(lines.positions.end(), {world(r, c), world(r + 1, c)});
  for (int r : lines_at(f.rows, f.depth, f.position[2]))
    for (int c = 0; c + 1 < f.columns; ++c)
      lines.positions.insert(lines.positions.end(), {world(r, c), world(r, c + 1)});
  return lines;
}

Mesh PlaneMesh(const double plane[4], const Eigen::Vector3d& around, double half) {
  const PlaneFrame f = MakePlaneFrame(plane);
  const Eigen::Vector3d centre = around - (f.n.dot(around) - f.offset) * f.n;
  auto p = [&](double su, double sv) -> V3 {
    return (centre + half * (su * f.u + sv * f.v)).cast<float>();
  };
  Mesh m;
  // Counter-clockwise seen from the normal's side: u x v = n.
  FlatQuad(&m, p(-1, -1), p(1, -1), p(1, 1), p(-1, 1));
  return m;
}

Lines PlaneGrid(const double plane[4], const Eigen::Vector3d& around, double half,
                double spacing) {
  Lines lines;
  if (spacing <= 0) return lines;
  const PlaneFrame f = MakePlaneFrame(plane);
  const Eigen::Vector3d origin = f.offset * f.n;  // the plane's point nearest the world origin
  const double cu = f.u.dot(around - origin), cv = f.v.dot(around - origin);
  auto p = [&](double u, double v) -> V3 { return (origin + u * f.u + v * f.v).cast<float>(); };
  const double u0 = std::ceil((cu - half) / spacing) * spacing;
  const double v0 = std::ceil((cv - half) / spacing) * spacing;
  for (double u = u0; u <= cu + half; u += spacing)
    lines.positions.insert(lines.positions.end(), {p(u, cv - half), p(u, cv + half)});
  for (double v = v0; v <= cv + half; v += spacing)
    lines.positions.insert(lines.positions.end(), {p(cu - half, v), p(cu + half, v)});
  return lines;
}

}  // namespace simpartner::viewer
