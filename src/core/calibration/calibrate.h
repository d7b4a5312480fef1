#pragma once
// Lens distortion calibration, the procedure of thesis 4.6 over one to four images of the
// calibration pattern (pattern.h), ideally rotated about +-45 deg about x and y with the
// target near the image centre (step 1 is the user's):
//  2. start from zero distortion;
//  3. reconstruct the pattern plane's pose from the target, with distortion correction by
//     the current estimate (the target sits in the nearly distortion-free centre);
//     with options.refine_pose (beyond the thesis, on by default) only the first
//     iteration does so: step 7 also corrects each image's pose from its spots
//     (distortion_fit.h: fitDistortionAndPoses), and the next iteration starts from the
//     corrected pose. The target's own pose errs by hundredths to tenths of a degree,
//     which at the pattern's edges, far from the target, is tenths of a pixel or more
//     (docs/calibration.md);
//  4. project the pattern's spots to their ideal image positions (matching.h);
//  5. find the spots' centres in the image (spots.h; done once, it needs no estimate);
//  6. match ideal to seen positions from the origin outwards (matching.h) and take the
//     displacements du, dv at the ideal positions;
//  7. solve k1, k2, p1, p2 by least squares over every usable image (eqs. 4.8-4.9,
//     distortion_fit.h);
//  8. repeat 3-7 until every parameter's relative change is below
//     options.relative_change (thesis: 0.01; distortion_fit.h says how it is measured).
//
// Errors, per image (the image is reported and left out of that iteration, the others go
// on): EmptyFrame, FrameSizeMismatch (not the size of the settings' camera), the spot
// threshold's error, the target's detection or reconstruction error (NoTarget, ...), TooFewMatches
// (fewer than options.min_matches spots matched: no pattern around the target),
// MatchAmbiguity (more than options.max_ambiguous_fraction of the spots ambiguous).
// For the whole calibration: the first image's error when no image is usable, DegenerateFit
// when the matches do not determine the parameters, Diverged when an estimate stops being a
// plausible lens (distortion_fit.h) or options.max_iterations pass without convergence,
// PoorCoverage when it converged but the matched spots do not reach far enough towards the
// image's corners (coverageRadiusFraction; the estimate is in the result all the same).
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <functional>
#include <span>
#include <vector>

#include "core/calibration/distortion_fit.h"
#include "core/calibration/matching.h"
#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/settings.h"

namespace imagepro {

struct SpotCorrespondence {
  Eigen::Vector2d pattern_mm = Eigen::Vector2d::Zero();  // the spot on the pattern (target frame, z = 0)
  Eigen::Vector2d ideal_px = Eigen::Vector2d::Zero();    // its ideal image position
  Eigen::Vector2d seen_px = Eigen::Vector2d::Zero();     // the matched spot centre in the image
};

// One image, as of the last iteration that measured it.
struct CalibrationImageReport {
  Status status = Status::Stopped;  // Ok: used
  Pose target_pose;                 // the pattern plane's pose from the target (first located)
  Pose pose;                        // the pose used last (corrected after it with refine_pose)
  int spots_found = 0;              // spot-like components in the image
  int spots_expected = 0;           // pattern spots whose ideal image lies in the image
  MatchStats match;
  std::vector<SpotCorrespondence> correspondences;
};

struct CalibrationIteration {
  int iteration = 0;  // 1-based
  Distortion distortion;          // the estimate this iteration produced
  double relative_change = 0.0;   // against the estimate it started from
  double rms_residual_px = 0.0;   // of the fit over the matched spots
  int matches = 0;
  int images_used = 0;
};

// How far out the matched spots reach, over every image used in the last iteration: the
// largest distance of a matched spot's ideal position from the principal point, as a
// fraction of the distance of the image's farthest corner. The fit extrapolates eq. 4.7
// beyond it, and the r^4 term goes wrong fast: a pattern seen too small (an A4 sheet 800 mm
// away with the thesis camera) fits with a residual of 0.02 px and a field wrong by a pixel
// or more at the corners. Below kMinCoverageRadiusFraction the calibration is PoorCoverage.
// The threshold is measured (docs/calibration.md, "Coverage"): over the printed A4 and A3
// pages at 300-1200 mm, views tilted 35 and 45 deg, every calibration reaching it stayed
// near half the 0.1 px goal, while most below it did not, some by pixels.
inline constexpr double kMinCoverageRadiusFraction = 0.6;
double coverageRadiusFraction(const CameraModel& camera, std::span<const CalibrationImageReport> images);

struct CalibrationResult {
  Status status = Status::Stopped;
  double coverage_radius_fraction = 0.0;  // of the last iteration's matches (coverageRadiusFraction)
  Distortion distortion;  // the last estimate
  bool converged = false;
  int iterations = 0;
  double rms_residual_px = 0.0;
  std::vector<CalibrationIteration> history;
  std::vector<CalibrationImageReport> images;
};

using IterationCallback = std::function<void(const CalibrationIteration&)>;

// Step 3: the pattern plane's pose from one image; camera.distortion is the current estimate.
using PatternLocator = std::function<Status(const cv::Mat& grey, const CameraModel& camera, Pose& pose)>;
// Detection of the target (thesis 2.6) and its reconstruction with distortion correction
// (thesis 4.5), with the settings' pipeline options.
PatternLocator targetPatternLocator(const Settings& settings);

// The procedure over `images` (CV_8UC1). `locator` empty: targetPatternLocator(settings).
// The result is filled whatever the status; `onIteration` sees each iteration as it ends.
Status calibrateDistortion(const Settings& settings, std::span<const cv::Mat> images, CalibrationResult& result,
                           const IterationCallback& onIteration = {}, const PatternLocator& locator = {});

// Steps 3-6 for any source of displacements: fills `samples` for the given estimate.
using DistortionMeasurement =
    std::function<Status(const Distortion& estimate, std::vector<DistortionSample>& samples)>;
// Receives each image's pose correction after a step 7 that solved for them.
using PoseCorrectionCallback = std::function<void(std::span<const PoseCorrection> corrections)>;
// Steps 2-8: the iteration from `start` (zero in the thesis) until convergence. Step 7 is
// eq. 4.8 alone (fitDistortion), or with the pose columns (fitDistortionAndPoses) when
// options.refine_pose and the samples name their images. result.images is left as it is.
Status iterateDistortion(const CameraModel& camera, const CalibrationOptions& options, const Distortion& start,
                         const DistortionMeasurement& measure, CalibrationResult& result,
                         const IterationCallback& onIteration = {},
                         const PoseCorrectionCallback& onPoseCorrection = {});

}  // namespace imagepro
