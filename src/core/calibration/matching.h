#pragma once
// Ideal spot positions and their matching to the spots seen (thesis 4.6 steps 4 and 6).
//
// Step 4: every pattern spot is projected with the pattern plane's pose by the ideal
// pinhole camera. Its ideal position is the centre of the ideal image of the spot's circle
// (the centroid of that ellipse, which is what the spot finder measures), not the image of
// the circle's centre.
//
// Step 6, from the origin outwards (thesis 4.3): the ideal spots are taken in order of
// their distance from the principal point. Each one's position as seen is predicted as
// its ideal position distorted by the current estimate plus the part of the displacement
// the estimate does not yet explain, taken as the mean residual of its already matched
// grid neighbours (8-neighbourhood, else 5x5; none near the origin, where the distortion
// vanishes). The observed spot nearest the prediction is its match when
//  * it lies within the gate, half the ideal image distance to the nearest grid node, and
//  * its area is within a factor kAreaTolerance of the spot's predicted image area.
// It is ambiguous (counted, not used) when a second candidate lies within the gate too, or
// when the nearest was already taken by another ideal spot: a correct prediction is within
// half a spacing of its own spot and more than half a spacing from every other, so either
// means an ideal position has come between the ideal and the seen position of another
// spot, the thesis's matching problem (or a spot-like blemish lies next to a spot).
// No candidate: the spot is missing (off the sheet, hidden, not found), which is harmless.
// Because the prediction carries the neighbours' displacement outwards, a match needs only
// the change of the unexplained displacement from one spot to the next to stay inside the
// gate, not the displacement itself (see spacing.h).
#include <Eigen/Core>

#include <span>
#include <vector>

#include "core/calibration/pattern.h"
#include "core/calibration/spots.h"
#include "core/common/geometry.h"

namespace imagepro {

inline constexpr double kAreaTolerance = 4.0;

struct IdealSpot {
  int spot = 0;  // index into the pattern's spot list
  int column = 0, row = 0;
  Eigen::Vector2d ideal = Eigen::Vector2d::Zero();  // undistorted px
  double area_px = 0.0;     // area of the spot's ideal image
  double spacing_px = 0.0;  // ideal image distance to the nearest neighbouring grid node
};

// Spots in front of the camera that the current estimate (camera.distortion) puts inside
// the image (a barrel lens draws in spots whose ideal position lies outside it), their
// ideal position at most a tenth of the image diagonal outside (farther out the model folds).
void projectPatternSpots(const CameraModel& camera, const PatternGeometry& pattern,
                         std::span<const PatternSpot> spots, const Pose& pose, std::vector<IdealSpot>& out);

struct SpotMatch {
  int ideal = 0;     // index into the ideal spots
  int observed = 0;  // index into the observed spots
  double prediction_error_px = 0.0;  // distance of the observed spot from its prediction
  double gate_px = 0.0;
};

struct MatchStats {
  int matched = 0;
  int ambiguous = 0;
  int missing = 0;
};

struct MatchWorkspace {
  std::vector<int> order;
  std::vector<int> nodeMatch;  // per grid node: the observed spot matched there, or -1
  std::vector<Eigen::Vector2d> nodeResidual;
  std::vector<int> claimedBy;  // per observed spot: the ideal spot that took it, or -1
  std::vector<int> cellStart, cellFill, cellItems;  // bucket grid over the observed spots
};

// `camera.distortion` is the current estimate. `neighbourPrediction` false predicts by the
// estimate alone (as if no spot had been matched yet; used to state the spacing rule).
void matchSpots(const CameraModel& camera, const PatternGeometry& pattern, std::span<const IdealSpot> ideal,
                std::span<const ObservedSpot> observed, bool neighbourPrediction, MatchWorkspace& ws,
                std::vector<SpotMatch>& matches, MatchStats& stats);

}  // namespace imagepro
