#pragma once
// A few damped Gauss-Newton (Levenberg-Marquardt) steps of the 6-DoF pose after the
// analytic one (pose.h), against what the image measured: the rim's undistorted sub-pixel
// edge points and the two spots' undistorted centroids.
//
// Why: the analytic pose takes the plane's normal from the rim's fitted conic, whose five
// parameters summarise the edge points, and weighs the centre spot in by a rule of thumb
// (pose.h). Near head-on the rim's normal depends on the square root of the ellipse's
// tiny ellipticity; the spots' images, which move linearly with the tilt, then carry most
// of the information. A least-squares fit of all residuals at once, each weighed by its
// expected error, uses both in proportion at every tilt.
//
// Residuals (ideal pixels): every contour point's Sampson distance to the image conic of
// the rim under the pose (imageConicOfTargetCircle: f / |grad f|, the first-order geometric
// distance), and each spot centroid's offset from where the pose puts it (its centre's
// image plus the perspective centroid offset, as spotReprojectionErrors). The rotation is
// updated as R <- R exp([d]x) (three parameters), T <- T + t; the Jacobians are analytic.
// The rim alone cannot see the rotation about the target's normal: the offset spot fixes it.
#include <Eigen/Core>

#include <array>
#include <span>

#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro {

struct ReconstructionConfig;
struct ReconstructionResult;

struct PoseRefinement {
  Pose pose;                              // the refined pose (the start when not Ok)
  int iterations = 0;                     // accepted steps
  double rim_error_px = 0.0;              // RMS Sampson distance of the contour points, at `pose`
  std::array<double, 2> spot_errors_px{};  // centre and offset spot, as spotReprojectionErrors, at `pose`
  double start_cost = 0.0, cost = 0.0;    // weighed sum of squares (px^2) at the start and at `pose`
};

// Refines `start`. Errors (the pose left at `start`): TooFewPoints (fewer than 5 contour
// points), SpotsNotFound (a spot centroid not finite), SingularConic (the start is not a
// finite pose, its plane passes through the camera, or the normal equations are singular),
// Diverged (the pose moved further than a refinement may: more than 10 deg or 10 % of the
// distance, i.e. towards another solution). When no step lowers the cost, the start is the
// minimum: Ok, with the start's measures.
Status refinePose(const CameraModel& cam, const TargetGeometry& target, std::span<const Eigen::Vector2d> contour,
                  const Eigen::Vector2d& centreSpotPx, const Eigen::Vector2d& offsetSpotPx, const Pose& start,
                  PoseRefinement& out);

// The reconstruction's refinement step (ReconstructionOptions::refine_pose), run after the
// analytic pose has passed the self-check: refines out.pose and, when the refined pose is
// still within the self-check's bounds, keeps it with its own self-check measures
// (spot_error_px, rim_error_px); otherwise leaves the analytic pose and its measures. The
// rim's two candidates (out.candidates) stay the analytic ones. Returns the refinement's
// status (PoseInconsistent when the refined pose left the bounds); the frame stays Ok
// either way.
Status refineReconstructedPose(const ReconstructionConfig& config, ReconstructionResult& out);

}  // namespace imagepro
