#include "simpartner/viewer/mesh.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "simpartner/rotation_between.h"

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
  return RotationBetween(Eigen::Vector3d::UnitY(), up).toRotationMatrix();
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

Mesh PointMassMesh(double radius) {
  Mesh m;
  const float r = static_cast<float>(radius);
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) {
        const V3 a(sx * r, 0, 0), b(0, sy * r, 0), c(0, 0, sz * r);
        // Counter-clockwise seen from outside when sx * sy * sz > 0.
        if (sx * sy * sz > 0)
          FlatTriangle(&m, a, b, c);
        else
          FlatTriangle(&m, a, c, b);
      }
  return m;
}

Mesh GeometryMesh(const geometry_t& g) {
  switch (g.kind) {
    case geometry_t::KIND_BOX: return BoxMesh(Eigen::Vector3d(g.size[0], g.size[1], g.size[2]));
    case geometry_t::KIND_SPHERE: return SphereMesh(g.size[0]);
    case geometry_t::KIND_CYLINDER: return CylinderMesh(g.size[0], g.size[1]);
    case geometry_t::KIND_CAPSULE: return CapsuleMesh(g.size[0], g.size[1]);
    case geometry_t::KIND_NONE: return PointMassMesh();
    default: return Mesh();
  }
}

double HeightfieldSample(const heightfield_t& f, int row, int column) {
  return f.scale * f.samples[static_cast<size_t>(row) * f.columns + column] + f.offset;
}

Eigen::Isometry3d HeightfieldPose(const heightfield_t& f, const Eigen::Vector3d& up) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = UpRotation(up);
  pose.translation() = Eigen::Vector3d(f.position[0], f.position[1], f.position[2]);
  return pose;
}

double HeightfieldSurface(const heightfield_t& f, double x, double z) {
  const double u = std::clamp((x + f.width / 2) / f.width, 0.0, 1.0) * (f.columns - 1);
  const double v = std::clamp((z + f.depth / 2) / f.depth, 0.0, 1.0) * (f.rows - 1);
  const int c = std::min(static_cast<int>(u), f.columns - 2);
  const int r = std::min(static_cast<int>(v), f.rows - 2);
  const double fu = u - c, fv = v - r;
  // HeightfieldMesh's triangles: (r, c) (r + 1, c) (r, c + 1) below the
  // diagonal from (r + 1, c) to (r, c + 1), (r, c + 1) (r + 1, c)
  // (r + 1, c + 1) beyond it.
  const double h01 = HeightfieldSample(f, r, c + 1), h10 = HeightfieldSample(f, r + 1, c);
  if (fu + fv <= 1.0) {
    const double h00 = HeightfieldSample(f, r, c);
    return h00 + fu * (h01 - h00) + fv * (h10 - h00);
  }
  const double h11 = HeightfieldSample(f, r + 1, c + 1);
  return h11 + (1.0 - fu) * (h10 - h11) + (1.0 - fv) * (h01 - h11);
}

namespace {

// Local (y-up) position of sample (row, column).
Eigen::Vector3d FieldPoint(const heightfield_t& f, int row, int column) {
  return Eigen::Vector3d(-f.width / 2 + f.width * column / (f.columns - 1),
                         HeightfieldSample(f, row, column),
                         -f.depth / 2 + f.depth * row / (f.rows - 1));
}

}  // namespace

Mesh HeightfieldMesh(const heightfield_t& f, const Eigen::Vector3d& up, const Eigen::Vector3f& low,
                     const Eigen::Vector3f& high) {
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
  auto color = [&](double height) {
    const float t = hi > lo ? static_cast<float>((height - lo) / (hi - lo)) : 1.0f;
    return Eigen::Vector3f(low + t * (high - low));
  };
  const size_t count = static_cast<size_t>(f.rows) * f.columns;
  m.positions.reserve(count);
  m.normals.reserve(count);
  m.colors.reserve(count);
  for (int r = 0; r < f.rows; ++r)
    for (int c = 0; c < f.columns; ++c) {
      m.positions.push_back((turn * FieldPoint(f, r, c) + at).cast<float>());
      m.normals.push_back((turn * local_normal(r, c)).cast<float>());
      m.colors.push_back(color(HeightfieldSample(f, r, c)));
    }
  auto index = [&](int r, int c) { return static_cast<uint32_t>(r * f.columns + c); };
  m.indices.reserve(static_cast<size_t>(f.rows - 1) * (f.columns - 1) * 6);
  for (int r = 0; r + 1 < f.rows; ++r)
    for (int c = 0; c + 1 < f.columns; ++c) {
      // Counter-clockwise seen from above (+y): (r, c) -> (r + 1, c) -> (r, c + 1).
      m.indices.insert(m.indices.end(), {index(r, c), index(r + 1, c), index(r, c + 1),
                                         index(r, c + 1), index(r + 1, c), index(r + 1, c + 1)});
    }
  return m;
}

namespace {

// Indices of the points of polyline (t[i], h[i]) that Douglas-Peucker keeps
// at `tolerance` (always the first and the last).
std::vector<int> Simplify(const std::vector<double>& t, const std::vector<double>& h,
                          double tolerance) {
  const int n = static_cast<int>(t.size());
  std::vector<bool> keep(static_cast<size_t>(n), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<int, int>> spans = {{0, n - 1}};
  while (!spans.empty()) {
    const auto [a, b] = spans.back();
    spans.pop_back();
    int worst = -1;
    double worst_error = tolerance;
    for (int i = a + 1; i < b; ++i) {
      const double chord = h[a] + (h[b] - h[a]) * (t[i] - t[a]) / (t[b] - t[a]);
      const double error = std::abs(h[i] - chord);
      if (error > worst_error) {
        worst_error = error;
        worst = i;
      }
    }
    if (worst < 0) continue;
    keep[static_cast<size_t>(worst)] = true;
    spans.push_back({a, worst});
    spans.push_back({worst, b});
  }
  std::vector<int> kept;
  for (int i = 0; i < n; ++i)
    if (keep[static_cast<size_t>(i)]) kept.push_back(i);
  return kept;
}

}  // namespace

Lines HeightfieldGrid(const heightfield_t& f, const Eigen::Vector3d& up, double spacing,
                      double lift, double tolerance) {
  Lines lines;
  if (!f.present || f.rows < 2 || f.columns < 2 || spacing <= 0) return lines;
  const Eigen::Matrix3d turn = UpRotation(up);
  const Eigen::Vector3d at(f.position[0], f.position[1], f.position[2]);
  const Eigen::Vector3d lift_local(0, lift, 0);
  auto world = [&](int r, int c) -> V3 {
    return (turn * (FieldPoint(f, r, c) + lift_local) + at).cast<float>();
  };
  // Sample indices nearest to each multiple of spacing, measured in world
  // coordinates along that axis so that lines continue onto the plane grid.
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
  auto add_line = [&](int count, const std::function<std::pair<int, int>(int)>& sample) {
    std::vector<double> t(static_cast<size_t>(count)), h(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
      t[static_cast<size_t>(i)] = i;
      h[static_cast<size_t>(i)] = HeightfieldSample(f, sample(i).first, sample(i).second);
    }
    const std::vector<int> kept = Simplify(t, h, tolerance);
    for (size_t k = 0; k + 1 < kept.size(); ++k) {
      const auto [r0, c0] = sample(kept[k]);
      const auto [r1, c1] = sample(kept[k + 1]);
      lines.positions.insert(lines.positions.end(), {world(r0, c0), world(r1, c1)});
    }
  };
  for (int c : lines_at(f.columns, f.width, f.position[0]))
    add_line(f.rows, [c](int i) { return std::make_pair(i, c); });
  for (int r : lines_at(f.rows, f.depth, f.position[2]))
    add_line(f.columns, [r](int i) { return std::make_pair(r, i); });
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
