#include "core/common/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace imagepro {

namespace {
constexpr double kDegPerRad = 180.0 / M_PI;
constexpr double kRadPerDeg = M_PI / 180.0;
}  // namespace

Eigen::Matrix3d rotationMatrix(const Pose& p) {
  using Eigen::AngleAxisd;
  using Eigen::Vector3d;
  return (AngleAxisd(p.rz_deg * kRadPerDeg, Vector3d::UnitZ()) *
          AngleAxisd(p.ry_deg * kRadPerDeg, Vector3d::UnitY()) *
          AngleAxisd(p.rx_deg * kRadPerDeg, Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d translation(const Pose& p) { return {p.tx_mm, p.ty_mm, p.tz_mm}; }

Pose poseFromRt(const Eigen::Matrix3d& R, const Eigen::Vector3d& T) {
  // R = Rz*Ry*Rx: R(2,0) = -sin(ry), R(2,1) = cos(ry) sin(rx), R(2,2) = cos(ry) cos(rx),
  // R(1,0) = sin(rz) cos(ry), R(0,0) = cos(rz) cos(ry).
  Pose p;
  const double sy = std::clamp(-R(2, 0), -1.0, 1.0);
  const double cy = std::hypot(R(2, 1), R(2, 2));
  p.ry_deg = std::atan2(sy, cy) * kDegPerRad;
  if (cy > 1e-9) {
    p.rx_deg = std::atan2(R(2, 1), R(2, 2)) * kDegPerRad;
    p.rz_deg = std::atan2(R(1, 0), R(0, 0)) * kDegPerRad;
  } else {
    // Gimbal lock: only rz - rx (or rz + rx) is defined; put it all in rz.
    p.rx_deg = 0.0;
    p.rz_deg = std::atan2(-R(0, 1), R(1, 1)) * kDegPerRad;
  }
  p.tx_mm = T.x();
  p.ty_mm = T.y();
  p.tz_mm = T.z();
  return p;
}

double rotationAngleBetweenDeg(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb) {
  // atan2 of sine and cosine stays accurate near 0 deg, where acos(cos) loses half the digits.
  const Eigen::Matrix3d D = Ra.transpose() * Rb;
  const Eigen::Vector3d axis(D(2, 1) - D(1, 2), D(0, 2) - D(2, 0), D(1, 0) - D(0, 1));
  return std::atan2(0.5 * axis.norm(), 0.5 * (D.trace() - 1.0)) * kDegPerRad;
}

Eigen::Vector2d projectIdeal(const CameraModel& cam, const Eigen::Vector3d& Pc) {
  return {cam.u0() + cam.fu() * Pc.x() / Pc.z(), cam.v0() + cam.fv() * Pc.y() / Pc.z()};
}

Eigen::Vector3d backProjectIdeal(const CameraModel& cam, const Eigen::Vector2d& uv) {
  return {(uv.x() - cam.u0()) / cam.fu(), (uv.y() - cam.v0()) / cam.fv(), 1.0};
}

Eigen::Vector2d distortPixel(const CameraModel& cam, const Eigen::Vector2d& undistorted) {
  const Eigen::Vector2d c(cam.u0(), cam.v0());
  return undistorted + distortionDelta(cam.distortion, undistorted - c);
}

}  // namespace imagepro
