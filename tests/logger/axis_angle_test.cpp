// Axis-angle of SPEC 6 at and near both singularities (angle 0 and pi),
// against rotations built here from axis and angle (Rodrigues' formula)
// and from quaternions, never from the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "simpartner/logger/axis_angle.h"

namespace simpartner::logger {
namespace {

using Vec = std::array<double, 3>;

Vec Unit(Vec v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

// R = cos a I + sin a [n]x + (1 - cos a) n n^T
Matrix3 Rodrigues(const Vec& n, double a) {
  const double c = std::cos(a), s = std::sin(a), t = 1 - c;
  Matrix3 r;
  r[0] = {c + t * n[0] * n[0], t * n[0] * n[1] - s * n[2], t * n[0] * n[2] + s * n[1]};
  r[1] = {t * n[0] * n[1] + s * n[2], c + t * n[1] * n[1], t * n[1] * n[2] - s * n[0]};
  r[2] = {t * n[0] * n[2] - s * n[1], t * n[1] * n[2] + s * n[0], c + t * n[2] * n[2]};
  return r;
}

// Exactly pi: R = 2 n n^T - I (symmetric, no skew part at all).
Matrix3 HalfTurn(const Vec& n) {
  Matrix3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i][j] = 2 * n[i] * n[j] - (i == j ? 1.0 : 0.0);
  return r;
}

double MaxDifference(const Matrix3& a, const Matrix3& b) {
  double d = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d = std::max(d, std::abs(a[i][j] - b[i][j]));
  return d;
}

void ExpectAxis(const Vec& expected, const AxisAngle& got, double tolerance) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.axis[k], expected[k], tolerance) << "component " << k;
  EXPECT_NEAR(got.axis[0] * got.axis[0] + got.axis[1] * got.axis[1] + got.axis[2] * got.axis[2],
              1.0, 1e-14);
}

const std::vector<Vec> kAxes = {
    {1, 0, 0},  {0, 1, 0},    {0, 0, 1},   {-1, 0, 0},  {0, -1, 0}, {0, 0, -1},
    Unit({1, 1, 0}), Unit({1, -1, 0}), Unit({1, 2, 3}), Unit({-1, 2, -3}), Unit({-3, -2, -1}),
    Unit({0.001, 1, -0.002})};

TEST(AxisAngleTest, IdentityIsAngleZeroAboutX) {
  Matrix3 identity{};
  for (int i = 0; i < 3; ++i) identity[i][i] = 1.0;
  const AxisAngle aa = AxisAngleFromRotation(identity);
  EXPECT_EQ(aa.angle, 0.0);
  EXPECT_EQ(aa.axis, (Vec{1, 0, 0}));
  const double q[4] = {1, 0, 0, 0};
  const AxisAngle from_q = AxisAngleFromQuaternion(q);
  EXPECT_EQ(from_q.angle, 0.0);
  EXPECT_EQ(from_q.axis, (Vec{1, 0, 0}));
}

TEST(AxisAngleTest, OrdinaryAnglesMatchSpecFormula) {
  // Away from 0 and pi the SPEC's acos((trace - 1) / 2) is well conditioned.
  for (const Vec& n : kAxes) {
    for (double a : {0.1, 0.5, 1.0, M_PI / 2, 2.0, 2.5, 3.0}) {
      const Matrix3 r = Rodrigues(n, a);
      const AxisAngle aa = AxisAngleFromRotation(r);
      EXPECT_NEAR(aa.angle, std::acos((r[0][0] + r[1][1] + r[2][2] - 1) / 2), 1e-12) << a;
      EXPECT_NEAR(aa.angle, a, 1e-12);
      ExpectAxis(n, aa, 1e-12);
    }
  }
}

TEST(AxisAngleTest, NearZeroKeepsTheAngleAndTheRotation) {
  for (const Vec& n : kAxes) {
    for (double a : {1e-15, 1e-12, 1e-9, 1e-6, 1e-3}) {
      const Matrix3 r = Rodrigues(n, a);
      const AxisAngle aa = AxisAngleFromRotation(r);
      EXPECT_NEAR(aa.angle, a, 1e-15 + 1e-12 * a) << "angle " << a;
      EXPECT_GE(aa.angle, 0.0);
      // The axis is only as good as the skew part (~1e-16 / angle)...
      if (a >= 1e-9) ExpectAxis(n, aa, 1e-6);
      // ...but whatever it is, it gives back the rotation.
      EXPECT_LT(MaxDifference(Rodrigues(aa.axis, aa.angle), r), 1e-15) << "angle " << a;
    }
  }
}

TEST(AxisAngleTest, ExactlyPiTakesSignsFromOffDiagonal) {
  // n and -n are the same half turn: the largest component comes out
  // positive, the others with the signs the off-diagonal terms give.
  for (const Vec& n : kAxes) {
    const AxisAngle aa = AxisAngleFromRotation(HalfTurn(n));
    EXPECT_DOUBLE_EQ(aa.angle, M_PI);
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(n[i]) > std::abs(n[k]) + 1e-12) k = i;
    const double sign = n[k] > 0 ? 1.0 : -1.0;
    ExpectAxis({sign * n[0], sign * n[1], sign * n[2]}, aa, 1e-14);
    EXPECT_GT(aa.axis[k], 0.0);
  }
}

TEST(AxisAngleTest, ExactlyPiFromQuaternionWithZeroW) {
  const Vec n = Unit({1, -2, 2});
  const double q[4] = {0.0, n[0], n[1], n[2]};
  const AxisAngle aa = AxisAngleFromQuaternion(q);
  EXPECT_DOUBLE_EQ(aa.angle, M_PI);
  // Largest |component| is y (-2/3): the axis comes out as -n.
  ExpectAxis({-n[0], -n[1], -n[2]}, aa, 1e-15);
}

TEST(AxisAngleTest, NearPiKeepsTheDirectionOfTheAxis) {
  // Below pi the direction is defined (n and -n are different rotations),
  // also for axes whose largest component is negative.
  for (const Vec& n : kAxes) {
    for (double d : {1e-12, 1e-9, 1e-6, 1e-3, 0.1}) {
      const Matrix3 r = Rodrigues(n, M_PI - d);
      const AxisAngle aa = AxisAngleFromRotation(r);
      EXPECT_NEAR(aa.angle, M_PI - d, 1e-14) << "pi - " << d;
      ExpectAxis(n, aa, 1e-9);
      EXPECT_LT(MaxDifference(Rodrigues(aa.axis, aa.angle), r), 1e-14);
    }
  }
}

TEST(AxisAngleTest, QuaternionsOfAnyLengthAndSign) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(0.0, M_PI);
  for (int i = 0; i < 2000; ++i) {
    const Vec n = Unit({normal(rng), normal(rng), normal(rng)});
    const double a = angle(rng);
    const double q[4] = {std::cos(a / 2), std::sin(a / 2) * n[0], std::sin(a / 2) * n[1],
                         std::sin(a / 2) * n[2]};
    for (double scale : {1.0, -1.0, 3.5, -0.01}) {
      const double scaled[4] = {q[0] * scale, q[1] * scale, q[2] * scale, q[3] * scale};
      const AxisAngle aa = AxisAngleFromQuaternion(scaled);
      EXPECT_NEAR(aa.angle, a, 1e-12);
      EXPECT_LE(aa.angle, M_PI);
      ExpectAxis(n, aa, 1e-9);
    }
  }
}

TEST(AxisAngleTest, RotationMatrixOfQuaternion) {
  // 90 degrees about z: x goes to y.
  const double q[4] = {std::cos(M_PI / 4), 0, 0, std::sin(M_PI / 4)};
  const Matrix3 r = RotationFromQuaternion(q);
  EXPECT_LT(MaxDifference(r, Matrix3{{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}}), 1e-15);
}

}  // namespace
}  // namespace simpartner::logger
