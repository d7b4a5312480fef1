#pragma once
// Shared helpers of the reconstruction tests: poses over the study's range and the exact
// image of the target's rim at a pose (the ground truth of the renderer).
#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "core/common/geometry.h"
#include "core/ellipse/direct_fit.h"
#include "core/ellipse/ellipse.h"

namespace imagepro::testing {

// Distance z along the optical axis, tilt of the target normal from the optical axis about
// an axis at `azimuthDeg` in the image plane, in-plane rotation `rzDeg`, centre at pixel (u, v).
inline Pose makePose(const CameraModel& cam, double z, double tiltDeg, double azimuthDeg,
                     double rzDeg, double u, double v) {
  constexpr double kDeg = M_PI / 180.0;
  const Eigen::Vector3d axis(std::cos(azimuthDeg * kDeg), std::sin(azimuthDeg * kDeg), 0);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(tiltDeg * kDeg, axis) *
                             Eigen::AngleAxisd(rzDeg * kDeg, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Vector3d T((u - cam.u0()) * z / cam.fu(), (v - cam.v0()) * z / cam.fv(), z);
  return poseFromRt(R, T);
}

// Points of a circle of the target plane as the camera sees them (distortion applied).
inline std::vector<Eigen::Vector2d> seenCircle(const CameraModel& cam, const Pose& pose, double x0,
                                               double y0, double radius, int n = 180) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const Eigen::Vector3d P = R * Eigen::Vector3d(x0 + radius * std::cos(a), y0 + radius * std::sin(a), 0) + T;
    pts.push_back(distortPixel(cam, projectIdeal(cam, P)));
  }
  return pts;
}

// The rim's ellipse as seen (best ellipse through the distorted rim), standing in for the
// detection stage.
inline Ellipse seenRimEllipse(const CameraModel& cam, const TargetGeometry& t, const Pose& pose) {
  const std::vector<Eigen::Vector2d> pts = seenCircle(cam, pose, 0, 0, t.radius_mm);
  EllipseFit fit;
  fitEllipseDirect(std::span<const Eigen::Vector2d>(pts), fit);
  return fit.ellipse;
}

// Angle between the target's normal and the line of sight to its centre: 0 when seen head-on.
inline double viewAngleDeg(const Pose& pose) {
  const Eigen::Vector3d n = rotationMatrix(pose).col(2);
  return std::acos(std::min(1.0, n.dot(translation(pose).normalized()))) * 180.0 / M_PI;
}

inline double rotationErrorDeg(const Pose& a, const Pose& b) {
  return rotationAngleBetweenDeg(rotationMatrix(a), rotationMatrix(b));
}
inline double positionErrorPercent(const Pose& truth, const Pose& est) {
  return 100.0 * (translation(truth) - translation(est)).norm() / translation(truth).norm();
}

inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

}  // namespace imagepro::testing
