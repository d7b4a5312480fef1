#pragma once
// The quality report of a full intrinsic calibration (intrinsics.h): where the dots fell in
// the image (a coverage map, as text and as a picture) and named warnings, each saying what
// to do, when the views leave the intrinsics poorly determined. The thresholds are rules
// of thumb of camera calibration, checked against the rendered views of the tests: a lens
// is only known where dots fell (the distortion is extrapolated elsewhere), and the focal
// length only separates from the distance in tilted views.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "core/calibration/intrinsics.h"

namespace imagepro {

inline constexpr int kCoverageColumns = 8, kCoverageRows = 6;
inline constexpr double kMinCoveredFraction = 0.7;   // of the cells
inline constexpr double kMinBorderFraction = 0.5;    // of the outer ring of cells
inline constexpr double kMinSteepestTiltDeg = 25.0;
inline constexpr int kRecommendedViews = 4;
inline constexpr double kMaxGoodRmsPx = 0.5;
inline constexpr double kMaxFocalDeviation = 0.005;  // one standard deviation, relative

struct CoverageMap {
  std::vector<int> views;  // per cell, row by row: how many used views put a dot there
  double covered_fraction = 0.0;
  double border_fraction = 0.0;
};
CoverageMap coverageMap(const IntrinsicsResult& result);

// One line per row of cells, each cell the number of views with a dot there (9 for more,
// '.' for none).
std::string coverageText(const CoverageMap& map);
// The image's size: the cells shaded by their views, every used dot drawn in its view's
// colour (BGR).
cv::Mat coverageImage(const IntrinsicsResult& result, const CoverageMap& map);

struct CalibrationWarning {
  std::string name;    // PoorCoverage, PoorBorderCoverage, NarrowViewAngles, OneTiltAxis, FewViews, HighReprojectionError, UncertainFocalLength
  std::string advice;  // what happened and what to do, one sentence
};
std::vector<CalibrationWarning> intrinsicsWarnings(const IntrinsicsResult& result, const CoverageMap& map);

}  // namespace imagepro
