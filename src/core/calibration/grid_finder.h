#pragma once
// Finds the dots of a dot grid (dot_grid.h) in a photograph and names each by its row and
// column, for the full intrinsic calibration (intrinsics.h).
//  1. Uneven light is flattened: each pixel is divided by the local white level, the
//     grey closing (dark detail removed) over a window wider than a dot, smoothed.
//  2. The dots are the project's own pattern spots (spots.h: dark components of
//     plausible size, centred by their darkness-weighted centroid), cut from the
//     flattened image and weighed on the image as seen (dividing by the estimated light,
//     wrong near the sheet's edge, moved the centres enough to bias fx by 0.1 %).
//  3. The grid among them:
//     - OpenCV's grids: cv::findCirclesGrid on those centres (no blob detector of its
//       own, so the same names and order as OpenCV gives them), the whole grid or nothing;
//       a symmetric grid it cannot order is taken up as a lattice as below when whole.
//     - The thesis pattern: a lattice grown from a seed dot whose four nearest
//       neighbours form a cross, each next dot looked for where the last step predicts
//       it, so any part of the sheet in view is named. The names are the lattice's own
//       (the seed's row and column unknown): the points are the pattern's, in a frame
//       shifted and turned on the plane by whole spacings, which changes each view's pose
//       but not the intrinsics. The target's card leaves a hole the lattice grows around;
//       a dot whose size differs from its neighbours' (the target's own spots) is dropped.
// The centres are the dots' image centroids, not the images of their centres: the
// calibration corrects that (intrinsics.h).
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "core/calibration/dot_grid.h"
#include "core/common/status.h"

namespace imagepro {

struct FoundDot {
  int column = 0, row = 0;
  Eigen::Vector2d object_mm = Eigen::Vector2d::Zero();  // on the pattern's plane
  Eigen::Vector2d image_px = Eigen::Vector2d::Zero();   // the dot's centroid as seen
  int area_px = 0;
};

struct GridDetection {
  Status status = Status::Stopped;
  int candidates = 0;  // dark spots found, dots of the grid or not
  bool partial = false;
  std::vector<FoundDot> dots;
};

// Fewest dots of a partial thesis grid that are used (fewer: GridNotFound).
inline constexpr int kMinPartialGridDots = 12;

// The image divided by its local white level, white at about 230 (CV_8UC1).
cv::Mat flattenIllumination(const cv::Mat& grey);

// EmptyFrame, InvalidPattern, GridNotFound, or Ok with out.dots filled.
Status findDotGrid(const cv::Mat& grey, const DotGridSpec& spec, GridDetection& out);

}  // namespace imagepro
