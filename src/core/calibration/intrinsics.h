#pragma once
// Full intrinsic calibration from three or more views of a planar dot grid (dot_grid.h):
// focal lengths fx, fy in pixels (so d0 for a given pixel size, and the pixel aspect),
// principal point, and the distortion k1, k2, p1, p2 (k3 on request). Beyond the thesis,
// which took d0, the pixel size and the principal point as known (thesis 4.6 finds the
// distortion alone: calibrate.h, which stays as its own mode).
//  1. The grid's dots in each image (grid_finder.h).
//  2. cv::calibrateCamera (Zhang's homography start, then Levenberg-Marquardt over the
//     intrinsics and every view's pose), OpenCV's model: pinhole in normalised
//     coordinates, x_d = x (1 + k1 r^2 + k2 r^4 + k3 r^6) + tangential terms.
//  3. A dot's centroid is not the image of its centre: under perspective the near half of
//     the circle looks larger. With each view's pose and the lens of step 2, each dot's
//     image centroid is predicted (its rim projected, the area centroid of that polygon)
//     and the offset from its projected centre taken off the measured centroid; then step
//     2 again, options.centre_correction_passes times.
//  4. A view whose reprojection RMS is far above the others' (a misnamed grid) is left
//     out (PoseInconsistent) and step 2 run once more.
// The distortion is also given in this project's model (eq. 4.7: pixels about the
// principal point, geometry.h's Distortion), the least-squares fit of its displacement
// field to OpenCV's over the image (exact for fx = fy without k3).
//
// Errors: InvalidPattern (dotGridSpecError), per image EmptyFrame, FrameSizeMismatch (not the
// first image's size), GridNotFound; for the whole: TooFewViews (fewer than three views
// with the grid), DegenerateFit (OpenCV could not solve, or a result that is no lens).
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/calibration/dot_grid.h"
#include "core/calibration/grid_finder.h"
#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro {

inline constexpr int kMinIntrinsicViews = 3;

struct IntrinsicsOptions {
  bool fit_k3 = false;               // OpenCV's k3 (a strongly curved wide-angle lens); else fixed at 0
  int centre_correction_passes = 2;  // step 3; 0: the dots' centroids as measured
};

struct IntrinsicsView {
  Status status = Status::Stopped;  // Ok: used
  int dots = 0;
  bool partial = false;
  double rms_px = 0.0;              // reprojection RMS of its dots
  double tilt_deg = 0.0;            // angle between the pattern's normal and the optical axis
  Eigen::Vector2d tilt_axis = Eigen::Vector2d::Zero();  // direction of the normal's image-plane part
  cv::Vec3d rvec, tvec;             // the pattern's pose (OpenCV's Rodrigues vector, mm)
  std::vector<FoundDot> found;      // as measured
  std::vector<Eigen::Vector2d> centre_offset_px;  // step 3's correction of each dot
};

// One standard deviation of each estimate, from calibrateCamera's covariance.
struct IntrinsicsDeviations {
  double fx = 0, fy = 0, cx = 0, cy = 0, k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
};

struct IntrinsicsResult {
  Status status = Status::Stopped;
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  std::array<double, 5> opencv_dist{};  // k1, k2, p1, p2, k3 (normalised model)
  Distortion distortion;                // this project's model (eq. 4.7)
  double model_fit_rms_px = 0.0;        // RMS of the two models' fields apart over the image
  IntrinsicsDeviations deviation;       // in OpenCV's units
  double rms_px = 0.0;                  // over every dot of every view used
  int views_used = 0;
  std::vector<IntrinsicsView> views;
};

// Step 1's progress: called with the images searched so far (0 before the first, all of
// them before the fit) and their number; false stops the calibration there (Stopped).
using IntrinsicsProgress = std::function<bool(int searched, int images)>;

// Steps 1-4 over `images` (CV_8UC1, all of one size).
Status calibrateIntrinsics(std::span<const cv::Mat> images, const DotGridSpec& spec, const IntrinsicsOptions& options,
                           IntrinsicsResult& result, const IntrinsicsProgress& progress = {});

// Steps 2-4 for dots already found: `views[i].found` and its status set by the caller.
Status calibrateFoundDots(std::vector<IntrinsicsView> views, cv::Size imageSize, const DotGridSpec& spec,
                          const IntrinsicsOptions& options, IntrinsicsResult& result);

// Where each dot's centroid lies in the image against its projected centre (step 3), for
// a dot of `diameter_mm` at `object_mm` of a view at (rvec, tvec).
Eigen::Vector2d dotCentroidOffsetPx(const cv::Matx33d& K, const std::vector<double>& dist, const cv::Vec3d& rvec,
                                    const cv::Vec3d& tvec, const Eigen::Vector2d& object_mm, double diameter_mm);

// This project's distortion nearest (least squares over a grid of the image) to OpenCV's
// coefficients `dist` (4, 5, 8, 12 or 14 of them) of camera matrix K; `rms_px` the field
// difference left.
Distortion distortionFromOpenCv(const cv::Matx33d& K, const std::vector<double>& dist, int width, int height,
                                double* rms_px = nullptr);
// OpenCV's k1, k2, p1, p2 (k3 = 0) nearest to this project's distortion of `camera`.
std::array<double, 5> openCvFromDistortion(const CameraModel& camera, double* rms_px = nullptr);

// The camera model of the result: its size, principal point and distortion, d0 = fx *
// sx for the camera's x pixel size sx, and sy = d0 / fy (the pixel aspect).
void applyIntrinsics(const IntrinsicsResult& result, CameraModel& camera);
// The camera matrix of a camera model.
cv::Matx33d cameraMatrix(const CameraModel& camera);

}  // namespace imagepro
