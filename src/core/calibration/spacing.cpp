#include "core/calibration/spacing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/calibration/matching.h"
#include "core/calibration/pattern.h"

namespace imagepro {

std::array<Pose, 4> recommendedCalibrationViews(double distance_mm) {
  return {Pose{45.0, 0.0, 0.0, 0.0, 0.0, distance_mm}, Pose{-45.0, 0.0, 0.0, 0.0, 0.0, distance_mm},
          Pose{0.0, 45.0, 0.0, 0.0, 0.0, distance_mm}, Pose{0.0, -45.0, 0.0, 0.0, 0.0, distance_mm}};
}

SpacingCheck checkSpotSpacing(const CameraModel& camera, const TargetGeometry& target,
                              const PatternGeometry& pattern, std::span<const Pose> views,
                              bool neighbourPrediction) {
  SpacingCheck check;
  check.all_matched = true;
  check.smallest_gap_px = std::numeric_limits<double>::infinity();
  CameraModel ideal = camera;
  ideal.distortion = {};
  std::vector<PatternSpot> spots;
  patternSpots(pattern, target, spots);
  std::vector<IdealSpot> projected;
  std::vector<ObservedSpot> seen;
  std::vector<SpotMatch> matches;
  MatchWorkspace ws;
  for (const Pose& view : views) {
    projectPatternSpots(ideal, pattern, spots, view, projected);
    seen.clear();
    for (const IdealSpot& s : projected) {
      seen.push_back({distortPixel(camera, s.ideal), static_cast<int>(std::lround(s.area_px))});
      const double radius = std::sqrt(s.area_px / M_PI);
      check.smallest_gap_px = std::min(check.smallest_gap_px, s.spacing_px - 2.0 * radius);
    }
    MatchStats stats;
    matchSpots(ideal, pattern, projected, seen, neighbourPrediction, ws, matches, stats);
    check.spots += static_cast<int>(projected.size());
    if (stats.ambiguous > 0 || stats.missing > 0 || matches.size() != projected.size()) check.all_matched = false;
    for (const SpotMatch& m : matches) {
      if (m.ideal != m.observed) check.all_matched = false;
      check.worst_ratio = std::max(check.worst_ratio, m.prediction_error_px / m.gate_px);
    }
  }
  check.unambiguous = check.spots > 0 && check.all_matched && check.worst_ratio <= kSpacingMargin &&
                      check.smallest_gap_px > kSpotClearancePx;
  return check;
}

PatternGeometry patternWithSpacing(const PatternGeometry& pattern, double spacing_mm) {
  const Eigen::Vector2d sheet = patternSheetSizeMm(pattern);
  auto oddCount = [&](double length) {
    int n = static_cast<int>(std::ceil(length / spacing_mm - 1e-9));
    return n % 2 == 0 ? n + 1 : n;
  };
  PatternGeometry p = pattern;
  p.spot_spacing_mm = spacing_mm;
  p.columns = std::max(1, oddCount(sheet.x()));
  p.rows = std::max(1, oddCount(sheet.y()));
  return p;
}

double minimumSpotSpacingMm(const CameraModel& camera, const TargetGeometry& target, const PatternGeometry& pattern,
                            std::span<const Pose> views, bool neighbourPrediction, double step_mm) {
  const Eigen::Vector2d sheet = patternSheetSizeMm(pattern);
  const double largest = std::min(sheet.x(), sheet.y());
  for (double s = std::floor(2.0 * pattern.spot_radius_mm / step_mm + 1.0) * step_mm; s <= largest; s += step_mm)
    if (checkSpotSpacing(camera, target, patternWithSpacing(pattern, s), views, neighbourPrediction).unambiguous)
      return s;
  return 0.0;
}

}  // namespace imagepro
