#include "simpartner/validate/analysis.h"

#include <Eigen/Dense>
#include <cmath>
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

double SkidSteerRadius(const SkidSteerVehicle& v) {
  // Plane coordinates: X forward along the rear half, Y to the left; the
  // joint at the origin. Unknowns: the joint's velocity (X, Y) and the yaw
  // rate w (the whole vehicle turns rigidly: the steering joint is held).
  struct Wheel {
    Eigen::Vector2d position, heading;
    double rim_speed, load;
  };
  const Eigen::Vector2d front_heading(std::cos(v.alpha), std::sin(v.alpha));
  const Eigen::Vector2d rear_heading(1.0, 0.0);
  std::vector<Wheel> wheels;
  const bool per_wheel = v.wheel_loads[0] > 0 && v.wheel_loads[1] > 0 && v.wheel_loads[2] > 0 &&
                         v.wheel_loads[3] > 0;
  int index = 0;
  for (const auto& [heading, sign, load] :
       {std::make_tuple(front_heading, 1.0, v.front_load),
        std::make_tuple(rear_heading, -1.0, v.rear_load)}) {
    const Eigen::Vector2d mid = sign * v.axle * heading;
    const Eigen::Vector2d left(-heading.y(), heading.x());
    const double left_load = per_wheel ? v.wheel_loads[index] : load;
    const double right_load = per_wheel ? v.wheel_loads[index + 1] : load;
    const bool two_edges = v.contact_half_width > 0.0;
    for (int k = 0; k < (two_edges ? 2 : 1); ++k) {
      const double edge = two_edges ? (k == 0 ? -v.contact_half_width : v.contact_half_width) : 0.0;
      const double share = two_edges ? 0.5 : 1.0;
      wheels.push_back({mid + (v.half_track + edge) * left, heading, v.v_left, share * left_load});
      wheels.push_back(
          {mid - (v.half_track + edge) * left, heading, v.v_right, share * right_load});
    }
    index += 2;
  }
  // Residual of the balance; eps smooths |slip| near zero for Newton.
  auto residual = [&](const Eigen::Vector3d& x, double eps) {
    Eigen::Vector3d r(0.0, 0.0, 0.0);
    for (const Wheel& w : wheels) {
      const Eigen::Vector2d velocity(x(0) - x(2) * w.position.y(), x(1) + x(2) * w.position.x());
      const Eigen::Vector2d slip = velocity - w.rim_speed * w.heading;
      const Eigen::Vector2d force = -v.mu * w.load * slip / std::sqrt(slip.squaredNorm() + eps * eps);
      r.head<2>() += force;
      r(2) += w.position.x() * force.y() - w.position.y() * force.x();
    }
    // Centripetal: the force balance includes m a, a = w x V at the joint.
    r(0) += v.mass * x(2) * x(1);
    r(1) -= v.mass * x(2) * x(0);
    return r;
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

}  // namespace simpartner::validate
