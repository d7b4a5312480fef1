#pragma once
// The live calibration check of thesis appendix A.1.1: with the "calibration" box ticked,
// every shown frame of the calibration pattern gets the pattern's ideal spot positions
// (thesis 4.6 step 4) from the pose the pipeline reconstructed for its target, the spots
// seen in the frame (step 5) and their matching (step 6), all with the settings' camera
// and its distortion as the current estimate. The operator places the pattern with them
// before capturing the calibration images: matched spots reaching the image's corners,
// none ambiguous. The same functions as the calibration's (calibrate.h), one frame at a time.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "core/calibration/matching.h"
#include "core/calibration/pattern.h"
#include "core/calibration/spots.h"
#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/settings.h"

namespace imagepro {

struct CalibrationCheck {
  // Ok; the spot finder's error (the spots then stay empty); Stopped when not computed.
  Status status = Status::Stopped;
  std::vector<Eigen::Vector2d> ideal;  // step 4: undistorted image px, the pattern's spots in the image
  std::vector<Eigen::Vector2d> seen;   // step 5: spot centres found in the frame (as seen)
  std::vector<std::pair<int, int>> matches;  // step 6: (ideal, seen) index pairs
  MatchStats stats;
};

// Kept between frames so steady-state checking allocates nothing new.
struct CalibrationCheckWorkspace {
  std::vector<PatternSpot> pattern;
  SpotFinderWorkspace finder;
  MatchWorkspace match;
  std::vector<IdealSpot> ideal;
  std::vector<ObservedSpot> observed;
  std::vector<SpotMatch> matches;
};

// `pose`: the target's (and so the pattern plane's) pose in the frame `grey` (CV_8UC1 of
// the settings' camera size: else FrameSizeMismatch, or EmptyFrame).
Status checkCalibrationView(const Settings& settings, const cv::Mat& grey, const Pose& pose,
                            CalibrationCheckWorkspace& ws, CalibrationCheck& out);

}  // namespace imagepro
