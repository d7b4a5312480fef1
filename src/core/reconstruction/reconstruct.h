#pragma once
// The reconstruction part of the pipeline (thesis 5.2.2, fig. 5.1): from a detected target
// to its pose. Crop the target's region and re-threshold it, extract the rim's contour
// points and the two spots (features.h), correct the lens distortion of those points
// (undistort.h, thesis 4.5), fit the rim's ellipse (direct fit, thesis 2.6.2) and solve
// the pose analytically (pose.h). Each step's status is kept; the first failure ends the
// chain and is the result's status. No heap allocation once the workspace and the result
// have grown to the largest target seen.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/ellipse/ellipse.h"
#include "core/reconstruction/features.h"
#include "core/reconstruction/pose.h"
#include "core/reconstruction/rim_fit.h"
#include "core/reconstruction/undistort.h"
#include "core/settings/settings.h"

namespace imagepro {

// Status of each step; Stopped for a step the chain did not reach.
struct ReconstructionSteps {
  Status crop = Status::Stopped;
  Status threshold = Status::Stopped;
  Status contour = Status::Stopped;
  Status spots = Status::Stopped;
  Status fit = Status::Stopped;
  Status pose = Status::Stopped;
  Status refine = Status::Stopped;  // Stopped also when refine_pose is off; its failure keeps the analytic pose
};

struct ReconstructionResult {
  Status status = Status::Stopped;
  ReconstructionSteps steps;
  cv::Rect crop;
  int threshold = -1;
  std::vector<Eigen::Vector2d> contour;      // image px as seen, for display
  std::vector<Eigen::Vector2d> contour_ideal;  // the same, distortion corrected: what was fitted
  SpotFeatures spots;                          // image px as seen
  Eigen::Vector2d centre_spot_ideal = Eigen::Vector2d::Zero();
  Eigen::Vector2d offset_spot_ideal = Eigen::Vector2d::Zero();
  Conic conic = Conic::Zero();  // the rim's ellipse in ideal (undistorted) pixels
  Ellipse ellipse;              // the same, geometric
  Pose pose;
  // The rim's two circles completed into poses, the one kept first (AmbiguousPose: the
  // better-fitting first), with the self-check's measures of the kept one.
  PoseCandidates candidates;
  double spot_error_px = 0.0;  // the larger of spotReprojectionErrors of the pose
  double rim_error_px = 0.0;   // RMS distance of the contour points from the pose's rim
  double blur_spread_px = 0.0;  // the rim's blur along its widest direction (features.h); 0 unknown
  // The share of the rim seen (rim_fit.h): 1 for a whole rim, less where an occluder hides
  // part of it; 0 before the fit. `contour` holds only the points on the rim.
  double rim_seen = 0.0;
  // The spots could not tell the two circles apart and their normals lie within twice
  // ambiguity_tolerance_deg: `pose` is the one halfway between the candidates.
  bool halfway_pose = false;
};

struct ReconstructionWorkspace {
  FeatureWorkspace features;
  RimFitWorkspace rim;
};

// What the reconstruction needs from the settings. A camera whose lens the Taylor inverse
// errs on by more than kTaylorInverseLimitPx inside the frame (undistort.h) gets the exact
// inverse: options.exact_undistortion is set, and exact_for_wide_lens says it was not asked.
struct ReconstructionConfig {
  CameraModel camera;
  TargetGeometry target;
  ThresholdOptions rethreshold;
  ReconstructionOptions options;
  bool exact_for_wide_lens = false;
};
ReconstructionConfig reconstructionConfig(const Settings& settings);

// Which inverse of the lens model corrects the features under `config`.
LensInverse lensInverse(const ReconstructionConfig& config);

// The self-check (docs/reconstruction.md): a pose passes when its spot error (the larger of
// the two spots') is within max_spot_error_px, its rim error within max_rim_error_px, and
// not both beyond kJointErrorShare of their limits. Either alone may be large on a pose that
// is right (a rim combed by interlacing, a spot under glare); both together are a pose that
// fits neither, as when an occluder bends the rim the pose was taken from.
inline constexpr double kJointErrorShare = 0.5;
bool passesSelfCheck(const ReconstructionOptions& options, double spotErrorPx, double rimErrorPx);

// `detected` is the rim's ellipse found by the detection stage in the image as seen;
// `frameThreshold` the threshold that stage used (for re-threshold None). A frame whose
// size is not the camera model's gives FrameSizeMismatch.
// `expected`, when given (a tracked stream's last pose), decides between the rim's two
// circles when the spots cannot (see ReconstructionOptions). `detectedSpots`, when given,
// are the boxes of the spots the detection stage found (TargetDetection::spot_boxes),
// taken when the reconstruction's own spot search finds no clear pair (extractSpots).
Status reconstructTarget(const ReconstructionConfig& config, const cv::Mat& grey,
                         const Ellipse& detected, int frameThreshold,
                         ReconstructionWorkspace& ws, ReconstructionResult& out,
                         const Pose* expected = nullptr, const std::array<cv::Rect, 2>* detectedSpots = nullptr);
Status reconstructTarget(const Settings& settings, const cv::Mat& grey, const Ellipse& detected,
                         int frameThreshold, ReconstructionWorkspace& ws,
                         ReconstructionResult& out);

}  // namespace imagepro
