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
#include <cstdint>
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

// Which inverse corrected a frame's features: none (no distortion, or correction off), the
// thesis's Taylor inverse, the exact one as the settings ask, or the exact one because the
// Taylor inverse errs by more than kTaylorInverseLimitPx inside this camera's frame.
enum class LensInverse : std::uint8_t { None, Taylor, Exact, ExactWideLens };
// "none", "taylor", "exact", "exact-wide-lens": the name the outputs give.
const char* lensInverseName(LensInverse inverse);

// A wide lens: where the Taylor inverse errs by more than this inside the frame,
// the reconstruction uses the exact inverse without being asked (reconstruct.h). The sub-pixel
// rim's points scatter by about as much, so a larger error of the correction would show in the
// pose. The thesis camera's Taylor inverse errs by 0.03 px over 640x480; a 1280x720 webcam
// lens with 40 px of barrel distortion at the corners by 0.09 px.
inline constexpr double kTaylorInverseLimitPx = 0.05;

// The Taylor inverse's largest error inside the camera's frame (px), on every pixel of the
// frame's border and a 16 px grid within (the error grows towards the border). Kept per
// thread for the last camera asked, so asking every frame costs a comparison.
double taylorInverseErrorPx(const CameraModel& cam);

}  // namespace imagepro
