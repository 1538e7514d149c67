// Camera maths without GL: where world points land in the image, worked out
// by hand from the pinhole model (focal length 1 / tan(fov / 2) in
// normalised device coordinates), and the mouse and key motions.
#include <gtest/gtest.h>

#include <cmath>

#include "simpartner/viewer/camera.h"
#include "simpartner/viewer/options.h"

namespace simpartner::viewer {
namespace {

constexpr int kWidth = 1280;
constexpr int kHeight = 720;

// Eye 5 m along +x from the target (yaw 0, pitch 0), y up, 45 deg fov.
Camera LevelCamera() {
  Camera c;
  c.target = Eigen::Vector3d(0, 1, 0);
  c.yaw = 0;
  c.pitch = 0;
  c.distance = 5;
  c.fov_y = M_PI / 4;
  return c;
}

TEST(CameraTest, TheTargetIsInTheMiddleOfTheImage) {
  const auto p = LevelCamera().Project(Eigen::Vector3d(0, 1, 0), kWidth, kHeight);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x(), 640, 1e-9);
  EXPECT_NEAR(p->y(), 360, 1e-9);
  EXPECT_TRUE(LevelCamera().Eye().isApprox(Eigen::Vector3d(5, 1, 0)));
}

TEST(CameraTest, PointsProjectByThePinholeModel) {
  const Camera c = LevelCamera();
  const double f = 1 / std::tan(M_PI / 8);  // 2.4142
  const double aspect = static_cast<double>(kWidth) / kHeight;
  // 1 m above the target, 5 m from the eye: ndc y = f / 5, image y up.
  auto above = c.Project(Eigen::Vector3d(0, 2, 0), kWidth, kHeight);
  ASSERT_TRUE(above.has_value());
  EXPECT_NEAR(above->y(), (1 - f / 5) / 2 * kHeight, 1e-9);
  EXPECT_NEAR(above->x(), 640, 1e-9);
  // Looking along -x with y up, the camera's right is -z.
  auto right = c.Project(Eigen::Vector3d(0, 1, -1), kWidth, kHeight);
  ASSERT_TRUE(right.has_value());
  EXPECT_NEAR(right->x(), (1 + f / aspect / 5) / 2 * kWidth, 1e-9);
  // Twice as far away: half the offset.
  auto far = c.Project(Eigen::Vector3d(-5, 2, 0), kWidth, kHeight);
  ASSERT_TRUE(far.has_value());
  EXPECT_NEAR(far->y(), (1 - f / 10) / 2 * kHeight, 1e-9);
  // Behind the eye: not in the image.
  EXPECT_FALSE(c.Project(Eigen::Vector3d(6, 1, 0), kWidth, kHeight).has_value());
}

TEST(CameraTest, YawAndPitchPlaceTheEye) {
  Camera c = LevelCamera();
  c.yaw = M_PI / 2;  // left of a robot facing +x is -z
  EXPECT_TRUE(c.Eye().isApprox(Eigen::Vector3d(0, 1, -5), 1e-12));
  c.yaw = 0;
  c.pitch = M_PI / 6;
  EXPECT_TRUE(c.Eye().isApprox(Eigen::Vector3d(5 * std::cos(M_PI / 6), 1 + 2.5, 0), 1e-12));
  // The target stays in the middle from any side.
  c.yaw = 2.0;
  c.pitch = -0.3;
  const auto p = c.Project(c.target, kWidth, kHeight);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->x(), 640, 1e-6);
  EXPECT_NEAR(p->y(), 360, 1e-6);
}

TEST(CameraTest, ZUpWorldsLookLevelToo) {
  Camera c = LevelCamera();
  c.up = Eigen::Vector3d::UnitZ();
  c.target = Eigen::Vector3d::Zero();
  // 1 m along up appears above the middle.
  const auto p = c.Project(Eigen::Vector3d(0, 0, 1), kWidth, kHeight);
  ASSERT_TRUE(p.has_value());
  EXPECT_LT(p->y(), 360 - 100);
  EXPECT_NEAR(p->x(), 640, 1e-9);
  EXPECT_NEAR(c.Forward().dot(c.up), 0, 1e-12);
}

TEST(CameraTest, OrbitClampsPitchAndZoomScalesDistance) {
  Camera c = LevelCamera();
  c.Orbit(0.5, 10);
  EXPECT_LT(c.pitch, M_PI / 2);
  EXPECT_NEAR(c.yaw, 0.5, 1e-12);
  c.Zoom(0.5);
  EXPECT_NEAR(c.distance, 2.5, 1e-12);
  c.Zoom(1e-9);
  EXPECT_GT(c.distance, 0);
}

TEST(CameraTest, PanKeepsThePointUnderTheCursor) {
  Camera c = LevelCamera();
  const Eigen::Vector3d point(0, 1.5, 0.5);
  const auto before = c.Project(point, kWidth, kHeight);
  c.Pan(40, -25, kHeight);
  const auto after = c.Project(point, kWidth, kHeight);
  ASSERT_TRUE(before && after);
  EXPECT_NEAR(after->x() - before->x(), 40, 1e-6);
  EXPECT_NEAR(after->y() - before->y(), -25, 1e-6);
}

TEST(CameraTest, FlyMovesAlongTheViewHeading) {
  Camera c = LevelCamera();  // looking along -x
  c.Fly(2, 0, 0);
  EXPECT_TRUE(c.target.isApprox(Eigen::Vector3d(-2, 1, 0)));
  c.Fly(0, 1, 0);  // left of looking along -x is +z
  EXPECT_TRUE(c.target.isApprox(Eigen::Vector3d(-2, 1, 1)));
  c.Fly(0, 0, 3);
  EXPECT_TRUE(c.target.isApprox(Eigen::Vector3d(-2, 4, 1)));
}

TEST(CameraTest, FramingCameraSeesTheWholeSphere) {
  const Eigen::Vector3d centre(3, 1, -2);
  const double radius = 1.2;
  const Camera c = FramingCamera(Eigen::Vector3d::UnitY(), centre, radius);
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                   Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, -1, 0)}) {
    const auto p = c.Project(centre + radius * d, kWidth, kHeight);
    ASSERT_TRUE(p.has_value());
    EXPECT_GT(p->x(), 0);
    EXPECT_LT(p->x(), kWidth);
    EXPECT_GT(p->y(), 0);
    EXPECT_LT(p->y(), kHeight);
  }
}

TEST(CameraTest, CameraSpecIsInDegrees) {
  CameraSpec spec;
  spec.target[1] = 2;
  spec.yaw_deg = 90;
  spec.pitch_deg = 0;
  spec.distance = 3;
  const Camera c = CameraFromSpec(spec, Eigen::Vector3d::UnitY());
  EXPECT_TRUE(c.Eye().isApprox(Eigen::Vector3d(0, 2, -3), 1e-12));
}

}  // namespace
}  // namespace simpartner::viewer
