#pragma once
// Lens distortion correction (thesis 4.5): maps distorted pixel coordinates back to
// undistorted (ideal pinhole) ones under the model of eq. 4.7, in pixels about the
// principal point (docs/conventions.md).
//  * undistortTaylor: the thesis's first-order Taylor inverse, eqs. 4.18-4.19, with the
//    partial derivatives of f_u, f_v (eqs. 4.15-4.16) written out analytically. One
//    evaluation, no iteration; error grows with the distortion (thesis: <= 1 px for its
//    camera over 640x480, <= 6 px for exaggerated parameters).
//  * undistortExact: Newton's method on x = y + f(y) (lens_model.h), started from the
//    Taylor value; converges to machine precision in a few steps wherever the model is
//    invertible.
// f and its partial derivatives are those of core/common/lens_model.h.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "core/common/geometry.h"

namespace imagepro {

// Absolute pixel coordinates: distorted -> undistorted.
Eigen::Vector2d undistortTaylor(const CameraModel& cam, const Eigen::Vector2d& distortedPx);
Eigen::Vector2d undistortExact(const CameraModel& cam, const Eigen::Vector2d& distortedPx,
                               int maxIterations = 6);

// In place over a set of points; `exact` selects undistortExact instead of the Taylor inverse.
// Does nothing when the camera has no distortion.
void undistortPoints(const CameraModel& cam, bool exact, std::span<Eigen::Vector2d> points);

// Error of a correction method over every pixel centre of the camera's image: each pixel is
// taken as a distorted position, its true undistorted position is the exact inverse.
struct UndistortionError {
  double max_px = 0.0;
  double rms_px = 0.0;
  double max_residual_exact_px = 0.0;  // |distort(undistortExact(x)) - x|, the exact inverse's own check
  double largest_displacement_px = 0.0;  // |undistortExact(x) - x|: how far the lens moves a pixel
  // The largest error among the pixels whose distance from the principal point lies in
  // [i, i + 1) px (thesis 4.5: the error grows towards the image's corners).
  std::vector<double> max_px_by_radius;
};
UndistortionError measureTaylorUndistortionError(const CameraModel& cam);

}  // namespace imagepro
