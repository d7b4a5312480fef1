#pragma once
// The distortion parameters from measured displacements (thesis 4.4, eqs. 4.8-4.11) and
// the measures the calibration reports: residual, relative change between iterations
// (thesis 4.6 step 8), and the difference of two distortion fields over the image.
//
// Eq. 4.8 stacks, per matched spot, the two rows of eq. 4.7 linear in (k1, k2, p1, p2):
//   du = u r^2 k1 + u r^4 k2 + 2uv p1 + (r^2 + 2u^2) p2
//   dv = v r^2 k1 + v r^4 k2 + (r^2 + 2v^2) p1 + 2uv p2
// with (u, v) the undistorted position relative to the principal point. Eq. 4.9 solves it
// by the pseudo-inverse (A^T A)^-1 A^T b; here the same least-squares solution is taken by
// a column-pivoting QR of A with its columns scaled to unit norm first, because the r^4
// column is some 1e5 times the r^2 column in pixel units and A^T A would lose half the
// digits of the double.
#include <Eigen/Core>

#include <functional>
#include <span>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro {

struct DistortionSample {
  Eigen::Vector2d undistorted = Eigen::Vector2d::Zero();  // relative to the principal point, px
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();        // seen minus ideal position, px
  // For fitDistortionAndPoses: the image the sample belongs to (-1: none) and how its seen
  // position moves with a correction of that image's pose (poseJacobian).
  int image = -1;
  Eigen::Matrix<double, 2, 6> pose_jacobian = Eigen::Matrix<double, 2, 6>::Zero();
};

// The two rows of A (eq. 4.10) of one sample.
Eigen::Matrix<double, 2, 4> distortionDesignRows(const Eigen::Vector2d& undistortedRel);

// TooFewMatches with fewer than kMinDistortionSamples samples; DegenerateFit when the
// samples do not determine the four parameters (e.g. all on one line through the origin).
inline constexpr int kMinDistortionSamples = 4;
Status fitDistortion(std::span<const DistortionSample> samples, Distortion& out);

// A small correction of a pattern pose: every point P of the pattern (camera frame) moves
// to exp([w]x) P + t; (w in rad, t in mm).
using PoseCorrection = Eigen::Matrix<double, 6, 1>;  // (w, t)
Pose correctedPose(const Pose& pose, const PoseCorrection& c);
// d(seen position)/d(correction) at zero for a pattern point at P (camera frame): the
// pinhole's Jacobian, then the distortion's (camera.distortion, the current estimate).
Eigen::Matrix<double, 2, 6> poseJacobian(const CameraModel& camera, const Eigen::Vector3d& P);

// Eq. 4.8 with six more columns per image, the linearised correction of that image's
// pose: delta = A x + J_pose c_image. Step 3 reconstructs the pattern plane from the
// target alone, whose pose errs by hundredths to tenths of a degree; far from the target
// that is tenths of a pixel of displacement or more, which eq. 4.8 alone would take for
// distortion. Solving both together (the same column-scaled QR) separates them. Samples with image < 0 carry no
// pose column. `corrections` gets one entry per image (zero for images without samples).
Status fitDistortionAndPoses(std::span<const DistortionSample> samples, Distortion& out,
                             std::vector<PoseCorrection>& corrections);

// Root mean square of |measured - modelled displacement| over the samples, px; with
// `corrections`, the modelled displacement includes each sample's image's pose correction.
double rmsResidualPx(const Distortion& d, std::span<const DistortionSample> samples,
                     std::span<const PoseCorrection> corrections = {});

// Thesis 4.6 step 8: the largest relative change |next_k - previous_k| / |next_k| over the
// four parameters. Each parameter is weighed by its largest displacement at the image's
// corners, and a parameter whose displacement there is below kNegligibleEffectPx is
// measured against that displacement instead of its own (a parameter that is truly zero
// would otherwise never settle: its estimate is noise whose relative change stays ~1).
inline constexpr double kNegligibleEffectPx = 0.1;
double relativeParameterChange(const CameraModel& camera, const Distortion& previous, const Distortion& next);

// A displacement field: undistorted pixel position (absolute) -> displacement in px.
using DisplacementField = std::function<Eigen::Vector2d(const Eigen::Vector2d& undistortedPx)>;
DisplacementField displacementField(const CameraModel& camera, const Distortion& d);

// Difference of two fields over every pixel centre of the camera's image (taken as the
// undistorted position), px.
struct FieldComparison {
  double rms_px = 0.0;
  double max_px = 0.0;
};
FieldComparison compareDisplacementFields(const CameraModel& camera, const DisplacementField& a,
                                          const DisplacementField& b);
FieldComparison compareDistortionFields(const CameraModel& camera, const Distortion& a, const Distortion& b);

// Whether an estimate can still be a lens: finite, its largest displacement over the image
// below a quarter of the image's diagonal, and undistorted -> distorted orientation
// preserving (Jacobian determinant above 0.5) everywhere on a 16 px grid over the image.
bool distortionPlausible(const CameraModel& camera, const Distortion& d);

}  // namespace imagepro
