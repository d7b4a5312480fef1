#pragma once
// The shared geometric vocabulary of ImagePro: camera model, target and pattern
// geometry, pose, and the lens distortion model (thesis eq. 4.7, lens_model.h).
// Conventions (docs/conventions.md, binding):
//  * image (u, v) in pixels, u right, v down, centre of the top-left pixel at (0, 0);
//  * camera frame X right, Y down, Z along the optical axis;
//    u = u0 + d0*X/(sx*Z), v = v0 + d0*Y/(sy*Z);
//  * P_camera = R * P_target + T, R = Rz(Rz) * Ry(Ry) * Rx(Rx), angles in degrees;
//  * distortion in pixels relative to the principal point:
//    distorted = undistorted + delta(undistorted).
#include <Eigen/Core>
#include <array>

#include "core/common/lens_model.h"

namespace imagepro {

struct CameraModel {
  int width = 640;
  int height = 480;
  std::array<double, 2> pixel_size_mm{0.01, 0.01};  // (sx, sy), mm per pixel
  double image_plane_distance_mm = 8.0;               // d0
  std::array<double, 2> principal_point_px{319.5, 239.5};
  Distortion distortion;

  // Focal lengths in pixels, d0/sx and d0/sy.
  double fu() const { return image_plane_distance_mm / pixel_size_mm[0]; }
  double fv() const { return image_plane_distance_mm / pixel_size_mm[1]; }
  double u0() const { return principal_point_px[0]; }
  double v0() const { return principal_point_px[1]; }
};

// The secondary passive target: a white disk with two black spots (thesis fig. 2.1).
struct TargetGeometry {
  double radius_mm = 50.0;       // R
  double spot_radius_mm = 6.0;   // r0
  double spot_offset_mm = 25.0;  // rf, centre-to-centre distance of the two spots
};

// The calibration pattern (thesis 4.3): a white sheet, the target on a black square
// card at the centre, and a grid of black spots centred on the target, without the
// grid spots that would touch the card.
struct PatternGeometry {
  double spot_spacing_mm = 25.0;
  double spot_radius_mm = 4.0;
  int columns = 61;
  int rows = 49;
  double card_size_mm = 130.0;
};

// Six configuration parameters of the target with respect to the camera.
struct Pose {
  double rx_deg = 0.0;
  double ry_deg = 0.0;
  double rz_deg = 0.0;
  double tx_mm = 0.0;
  double ty_mm = 0.0;
  double tz_mm = 1000.0;
};

// R = Rz(rz) * Ry(ry) * Rx(rx).
Eigen::Matrix3d rotationMatrix(const Pose& pose);
Eigen::Vector3d translation(const Pose& pose);
// Inverse of rotationMatrix: angles in degrees, rx and rz in (-180, 180], ry in [-90, 90].
Pose poseFromRt(const Eigen::Matrix3d& R, const Eigen::Vector3d& T);

// Angle in degrees of the rotation R_a^-1 * R_b (the rotation error measure).
double rotationAngleBetweenDeg(const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb);

// Pinhole projection of a camera-frame point to ideal (undistorted) pixels.
Eigen::Vector2d projectIdeal(const CameraModel& cam, const Eigen::Vector3d& Pc);
// Ray direction (camera frame, z = 1) through an ideal (undistorted) pixel.
Eigen::Vector3d backProjectIdeal(const CameraModel& cam, const Eigen::Vector2d& uv);

// Absolute pixel coordinates: undistorted -> distorted (forward model of lens_model.h, exact).
Eigen::Vector2d distortPixel(const CameraModel& cam, const Eigen::Vector2d& undistorted);

}  // namespace imagepro
