#include "simpartner/validate/analysis.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <tuple>

namespace simpartner::validate {

CircleFit FitCircle(const std::vector<Eigen::Vector2d>& points) {
  CircleFit fit;
  const size_t n = points.size();
  if (n < 3) return fit;
  // Kasa: x^2 + y^2 + D x + E y + F = 0, linear in D, E, F. Centred on the
  // mean for conditioning.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(n);
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd b(n);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = points[i] - mean;
    a(static_cast<Eigen::Index>(i), 0) = p.x();
    a(static_cast<Eigen::Index>(i), 1) = p.y();
    a(static_cast<Eigen::Index>(i), 2) = 1.0;
    b(static_cast<Eigen::Index>(i)) = -p.squaredNorm();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 3) return fit;  // collinear (or repeated) points
  const Eigen::Vector3d def = qr.solve(b);
  Eigen::Vector2d centre(-def.x() / 2.0, -def.y() / 2.0);
  double r2 = centre.squaredNorm() - def.z();
  if (!(r2 > 0.0) || !std::isfinite(r2)) return fit;
  double radius = std::sqrt(r2);
  // Gauss-Newton on the residuals |p - c| - r.
  for (int iteration = 0; iteration < 50; ++iteration) {
    Eigen::MatrixXd j(n, 3);
    Eigen::VectorXd residual(n);
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d d = points[i] - mean - centre;
      const double distance = d.norm();
      if (distance == 0.0) return fit;
      const auto row = static_cast<Eigen::Index>(i);
      residual(row) = distance - radius;
      j(row, 0) = -d.x() / distance;
      j(row, 1) = -d.y() / distance;
      j(row, 2) = -1.0;
    }
    const Eigen::Vector3d step = j.colPivHouseholderQr().solve(-residual);
    centre += step.head<2>();
    radius += step.z();
    if (step.norm() < 1e-13 * (1.0 + radius)) break;
  }
  fit.centre = centre + mean;
  fit.radius = radius;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double deviation = std::abs((p - fit.centre).norm() - radius);
    fit.worst_deviation = std::max(fit.worst_deviation, deviation);
    sum += deviation * deviation;
  }
  fit.rms_deviation = std::sqrt(sum / static_cast<double>(n));
  fit.ok = std::isfinite(radius) && radius > 0.0;
  return fit;
}

Eigen::Vector2d FitLine(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  if (x.size() < 2) return Eigen::Vector2d(y.empty() ? 0.0 : y[0], 0.0);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double denominator = n * sxx - sx * sx;
  if (denominator == 0.0) return Eigen::Vector2d(sy / n, 0.0);
  const double slope = (n * sxy - sx * sy) / denominator;
  return Eigen::Vector2d((sy - slope * sx) / n, slope);
}

double Mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

namespace {

// One contact of the ideal vehicle in the plane of SkidSteerRadius.
struct SkidSteerContact {
  Eigen::Vector2d position, heading;
  double rim_speed, load;
  bool left, front;
  int edge;  // -1 inner rim edge, +1 outer, 0 a point wheel
};

// Plane coordinates: X forward along the rear half, Y to the left; the
// joint at the origin.
std::vector<SkidSteerContact> SkidSteerContacts(const SkidSteerVehicle& v) {
  const Eigen::Vector2d front_heading(std::cos(v.alpha), std::sin(v.alpha));
  const Eigen::Vector2d rear_heading(1.0, 0.0);
  std::vector<SkidSteerContact> contacts;
  const bool per_wheel = v.wheel_loads[0] > 0 && v.wheel_loads[1] > 0 && v.wheel_loads[2] > 0 &&
                         v.wheel_loads[3] > 0;
  int index = 0;
  for (const auto& [heading, sign, load] :
       {std::make_tuple(front_heading, 1.0, v.front_load),
        std::make_tuple(rear_heading, -1.0, v.rear_load)}) {
    const bool front = sign > 0.0;
    const Eigen::Vector2d mid = sign * v.axle * heading;
    const Eigen::Vector2d left(-heading.y(), heading.x());
    const double left_load = per_wheel ? v.wheel_loads[index] : load;
    const double right_load = per_wheel ? v.wheel_loads[index + 1] : load;
    const bool two_edges = v.contact_half_width > 0.0;
    // Edge -1 is the one nearer the middle.
    auto share = [&](int wheel, int edge) {
      if (edge == 0) return 1.0;
      const double middle = v.middle_edge_share[wheel] > 0.0 ? v.middle_edge_share[wheel] : 0.5;
      return edge < 0 ? middle : 1.0 - middle;
    };
    for (int k = 0; k < (two_edges ? 2 : 1); ++k) {
      const int edge = two_edges ? (k == 0 ? -1 : 1) : 0;
      const double offset = edge * v.contact_half_width;
      contacts.push_back({mid + (v.half_track + offset) * left, heading, v.v_left,
                          share(index, edge) * left_load, true, front, edge});
      contacts.push_back({mid - (v.half_track + offset) * left, heading, v.v_right,
                          share(index + 1, edge) * right_load, false, front, edge});
    }
    index += 2;
  }
  return contacts;
}

// Force (X, Y) and moment about the joint of the sliding contacts (all but
// those skipped) and of the centripetal force, for the joint's velocity
// (X, Y) and yaw rate x(2); eps smooths |slip| near zero for Newton.
Eigen::Vector3d SkidSteerBalance(const SkidSteerVehicle& v,
                                 const std::vector<SkidSteerContact>& contacts,
                                 const Eigen::Vector3d& x, double eps,
                                 const std::vector<bool>& skipped = {}) {
  Eigen::Vector3d r(0.0, 0.0, 0.0);
  for (size_t i = 0; i < contacts.size(); ++i) {
    if (i < skipped.size() && skipped[i]) continue;
    const SkidSteerContact& c = contacts[i];
    const Eigen::Vector2d velocity(x(0) - x(2) * c.position.y(), x(1) + x(2) * c.position.x());
    const Eigen::Vector2d slip = velocity - c.rim_speed * c.heading;
    const double speed = std::sqrt(slip.squaredNorm() + eps * eps);
    // Rolling (to rounding): no sliding force. Held contacts are skipped;
    // one that rolls by the way is counted as carrying nothing, so what the
    // held ones need is an upper bound.
    if (speed < 1e-12) continue;
    const Eigen::Vector2d force = -v.mu * c.load * slip / speed;
    r.head<2>() += force;
    r(2) += c.position.x() * force.y() - c.position.y() * force.x();
  }
  // Centripetal: the force balance includes m a, a = w x V at the joint.
  r(0) += v.mass * x(2) * x(1);
  r(1) -= v.mass * x(2) * x(0);
  return r;
}

}  // namespace

double SkidSteerRadius(const SkidSteerVehicle& v) {
  // Unknowns: the joint's velocity (X, Y) and the yaw rate w (the whole
  // vehicle turns rigidly: the steering joint is held).
  const std::vector<SkidSteerContact> contacts = SkidSteerContacts(v);
  auto residual = [&](const Eigen::Vector3d& x, double eps) {
    return SkidSteerBalance(v, contacts, x, eps);
  };
  const double speed = (v.v_left + v.v_right) / 2.0;
  Eigen::Vector3d x(speed, 0.0, speed * std::tan(v.alpha / 2.0) / v.axle);
  for (const double eps : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5, 1e-6}) {
    for (int iteration = 0; iteration < 100; ++iteration) {
      const Eigen::Vector3d f = residual(x, eps);
      Eigen::Matrix3d j;
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d dx = Eigen::Vector3d::Zero();
        dx(k) = 1e-8;
        j.col(k) = (residual(x + dx, eps) - f) / 1e-8;
      }
      const Eigen::Vector3d step = j.colPivHouseholderQr().solve(-f);
      double damping = 1.0;
      while (damping > 1e-4 && residual(x + damping * step, eps).squaredNorm() >= f.squaredNorm())
        damping /= 2.0;
      x += damping * step;
      if (step.norm() < 1e-13) break;
    }
  }
  if (!x.allFinite() || x(2) == 0.0) return std::nan("");
  const Eigen::Vector2d centre(-x(1) / x(2), x(0) / x(2));
  return (Eigen::Vector2d(-v.axle, 0.0) - centre).norm();
}

SkidSteerRolling SkidSteerRollingInnerWheels(const SkidSteerVehicle& v) {
  SkidSteerRolling best;
  const std::vector<SkidSteerContact> contacts = SkidSteerContacts(v);
  // The turn's centre where the two axle lines cross: on the rear one
  // (X = -a) and on the front one (through a (cos alpha, sin alpha) along
  // (-sin alpha, cos alpha)).
  const double s = (v.axle + v.axle * std::cos(v.alpha)) / std::sin(v.alpha);
  const Eigen::Vector2d centre = Eigen::Vector2d(v.axle * std::cos(v.alpha), v.axle * std::sin(v.alpha)) +
                                 s * Eigen::Vector2d(-std::sin(v.alpha), std::cos(v.alpha));
  const bool inner_left = v.alpha > 0.0;
  for (const int edge : {-1, 0, 1}) {
    std::vector<bool> sticking(contacts.size(), false);
    std::vector<size_t> held;
    for (size_t i = 0; i < contacts.size(); ++i) {
      if (contacts[i].left == inner_left && contacts[i].edge == edge) {
        sticking[i] = true;
        held.push_back(i);
      }
    }
    if (held.size() != 2) continue;  // no such edge (point wheels, or only points)
    // Rolling about the centre at the rate that gives the held rear edge
    // its rim speed; by the vehicle's symmetry the front one has it too.
    const SkidSteerContact& rear = contacts[held[0]].front ? contacts[held[1]] : contacts[held[0]];
    const Eigen::Vector2d arm = rear.position - centre;
    const double w = rear.rim_speed / -arm.y();
    const Eigen::Vector3d x(w * centre.y(), -w * centre.x(), w);
    // Forces F1, F2 at the held edges balance the rest:
    // F1 + F2 = -r.xy, p1 x F1 + p2 x F2 = -r.z (3 equations, 4 unknowns).
    const Eigen::Vector3d r = SkidSteerBalance(v, contacts, x, 0.0, sticking);
    const Eigen::Vector2d p1 = contacts[held[0]].position, p2 = contacts[held[1]].position;
    Eigen::Matrix<double, 3, 4> a;
    a << 1, 0, 1, 0,  //
        0, 1, 0, 1,   //
        -p1.y(), p1.x(), -p2.y(), p2.x();
    const Eigen::Vector4d particular = a.completeOrthogonalDecomposition().solve(-r);
    const Eigen::FullPivLU<Eigen::Matrix<double, 3, 4>> lu(a);
    const Eigen::Vector4d null = lu.kernel().col(0).normalized();
    const double n1 = v.mu * contacts[held[0]].load, n2 = v.mu * contacts[held[1]].load;
    auto ratio = [&](double lambda) {
      const Eigen::Vector4d f = particular + lambda * null;
      return std::max(f.head<2>().norm() / n1, f.tail<2>().norm() / n2);
    };
    // The larger of two convex functions of lambda: convex; golden section.
    double lo = -10.0 * (n1 + n2) / v.mu - particular.norm(), hi = -lo;
    const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int k = 0; k < 200; ++k) {
      const double m1 = hi - golden * (hi - lo), m2 = lo + golden * (hi - lo);
      if (ratio(m1) < ratio(m2)) hi = m2; else lo = m1;
    }
    const double needed = ratio((lo + hi) / 2.0);
    // Check the held edges really roll at their rim speed.
    double worst_slip = 0.0;
    for (const size_t i : held) {
      const SkidSteerContact& c = contacts[i];
      const Eigen::Vector2d velocity(x(0) - x(2) * c.position.y(), x(1) + x(2) * c.position.x());
      worst_slip = std::max(worst_slip, (velocity - c.rim_speed * c.heading).norm());
    }
    if (worst_slip > 1e-9 || !(needed < best.friction_needed)) continue;
    best.friction_needed = needed;
    best.edge = edge;
    best.radius = (Eigen::Vector2d(-v.axle, 0.0) - centre).norm();
  }
  return best;
}

}  // namespace simpartner::validate
