#pragma once
// The spot spacing of the calibration pattern (thesis 4.3). A denser grid gives more
// measurements, but "ideal position of an outer spot may appear between the ideal position
// and distorted position of an inner spot": below some spacing the matching fails. The
// thesis takes "the minimum possible value which does not create matching problems"; this
// file states that rule as a computation, for the matching this project does (matching.h)
// and the lens one expects:
//
// A spacing is unambiguous for a camera, its expected distortion and the calibration views
// when, in the first iteration (estimate zero, so the whole distortion is unexplained) and
// with spot centres exactly where the lens puts them,
//  1. every visible spot is matched to its own image, and none is ambiguous or missing;
//  2. every prediction lies within kSpacingMargin of its gate (half the local spacing) of
//     its spot, leaving the rest for the spot centres' noise and the error of the pose the
//     target gives in the first iteration;
//  3. neighbouring spots stay apart in the image by more than kSpotClearancePx, the clear
//     white ring the spot finder wants around each spot (spots.h).
// minimumSpotSpacingMm is the smallest such spacing, the sheet kept the same size.
//
// With neighbour prediction the unexplained displacement only has to change by less than
// half a spacing from one spot to the next, so condition 3 usually decides; matching by the
// ideal positions alone (neighbourPrediction false, the thesis's matching as written)
// needs the displacement itself below a quarter of the spacing everywhere, which is what
// makes the thesis's spacing depend on the distortion.
#include <array>
#include <span>

#include "core/calibration/spots.h"
#include "core/common/geometry.h"

namespace imagepro {

inline constexpr double kSpacingMargin = 0.5;

// The thesis's calibration views (4.6 step 1): the pattern rotated +45 and -45 deg about
// x, then about y, its target on the optical axis at `distance_mm`.
std::array<Pose, 4> recommendedCalibrationViews(double distance_mm);

struct SpacingCheck {
  bool unambiguous = false;  // conditions 1 to 3 hold in every view
  bool all_matched = false;  // condition 1
  double worst_ratio = 0.0;  // condition 2: largest prediction error over its gate
  double smallest_gap_px = 0.0;  // condition 3: smallest image gap between neighbouring spots
  int spots = 0;             // visible spots over all views
};

// `camera.distortion` is the expected distortion.
SpacingCheck checkSpotSpacing(const CameraModel& camera, const TargetGeometry& target,
                              const PatternGeometry& pattern, std::span<const Pose> views,
                              bool neighbourPrediction = true);

// The pattern with spacing s and the sheet of `pattern` (columns and rows rounded up to cover
// it, odd so that a spot row and column pass through the target).
PatternGeometry patternWithSpacing(const PatternGeometry& pattern, double spacing_mm);

// The smallest unambiguous spacing, searched in steps of `step_mm` from just above two spot
// radii up to the sheet's smaller side; 0 when none is.
double minimumSpotSpacingMm(const CameraModel& camera, const TargetGeometry& target, const PatternGeometry& pattern,
                            std::span<const Pose> views, bool neighbourPrediction = true, double step_mm = 0.5);

}  // namespace imagepro
