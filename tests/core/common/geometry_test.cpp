#include "core/common/geometry.h"

#include <gtest/gtest.h>

#include <random>

namespace imagepro {
namespace {

TEST(Geometry, IdentityPoseFacesCameraWithOffsetSpotToTheRight) {
  CameraModel cam;
  Pose pose;  // identity rotation, 1000 mm ahead
  const Eigen::Vector3d spot = rotationMatrix(pose) * Eigen::Vector3d(25, 0, 0) + translation(pose);
  const Eigen::Vector2d uv = projectIdeal(cam, spot);
  EXPECT_GT(uv.x(), cam.u0());
  EXPECT_DOUBLE_EQ(uv.y(), cam.v0());
  // +Z of the target points away from the camera.
  EXPECT_GT((rotationMatrix(pose) * Eigen::Vector3d::UnitZ()).z(), 0.0);
}

TEST(Geometry, RotationOrderIsRzRyRx) {
  Pose p;
  p.rx_deg = 90;
  p.rz_deg = 90;
  // Rx(90) maps Y to Z; Rz(90) leaves Z alone: so Y -> Z.
  const Eigen::Vector3d y = rotationMatrix(p) * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(y.z(), 1.0, 1e-12);
  // Rx(90) leaves X; Rz(90) maps X to Y.
  const Eigen::Vector3d x = rotationMatrix(p) * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x.y(), 1.0, 1e-12);
}

TEST(Geometry, PoseRoundTripsThroughRotationMatrix) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> a(-179, 179), b(-89, 89);
  for (int i = 0; i < 1000; ++i) {
    Pose p{a(rng), b(rng), a(rng), 1, 2, 3};
    const Pose q = poseFromRt(rotationMatrix(p), translation(p));
    EXPECT_NEAR(q.rx_deg, p.rx_deg, 1e-9);
    EXPECT_NEAR(q.ry_deg, p.ry_deg, 1e-9);
    EXPECT_NEAR(q.rz_deg, p.rz_deg, 1e-9);
    EXPECT_NEAR(rotationAngleBetweenDeg(rotationMatrix(p), rotationMatrix(q)), 0.0, 1e-6);
  }
}

TEST(Geometry, RotationAngleBetween) {
  Pose a, b;
  b.ry_deg = 30;
  EXPECT_NEAR(rotationAngleBetweenDeg(rotationMatrix(a), rotationMatrix(b)), 30.0, 1e-9);
}

TEST(Geometry, ProjectionAndBackProjectionAgree) {
  CameraModel cam;
  const Eigen::Vector3d P(120, -80, 900);
  const Eigen::Vector2d uv = projectIdeal(cam, P);
  EXPECT_NEAR(uv.x(), 319.5 + 800.0 * 120 / 900, 1e-12);
  const Eigen::Vector3d ray = backProjectIdeal(cam, uv);
  EXPECT_NEAR(ray.x() * 900, 120, 1e-9);
  EXPECT_NEAR(ray.y() * 900, -80, 1e-9);
}

}  // namespace
}  // namespace imagepro
