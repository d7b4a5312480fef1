#include "core/calibration/pattern.h"

#include <algorithm>
#include <cmath>

namespace imagepro {

double patternCardHalfMm(const PatternGeometry& pattern, const TargetGeometry& target) {
  return std::max(0.5 * pattern.card_size_mm, target.radius_mm);
}

double patternSpotRadiusMm(const PatternGeometry& pattern) {
  return std::min(pattern.spot_radius_mm, 0.5 * pattern.spot_spacing_mm);
}

Eigen::Vector2d patternSheetSizeMm(const PatternGeometry& pattern) {
  return {std::max(pattern.columns, 1) * pattern.spot_spacing_mm,
          std::max(pattern.rows, 1) * pattern.spot_spacing_mm};
}

Eigen::Vector2d patternNodeMm(const PatternGeometry& pattern, int column, int row) {
  // The grid is centred on the target: with an odd count a node sits on the centre.
  const double colCentre = 0.5 * (std::max(pattern.columns, 1) - 1.0);
  const double rowCentre = 0.5 * (std::max(pattern.rows, 1) - 1.0);
  return {(column - colCentre) * pattern.spot_spacing_mm, (row - rowCentre) * pattern.spot_spacing_mm};
}

bool patternSpotTouchesCard(const PatternGeometry& pattern, const TargetGeometry& target, int column,
                            int row) {
  const Eigen::Vector2d c = patternNodeMm(pattern, column, row);
  const double half = patternCardHalfMm(pattern, target);
  const double r = patternSpotRadiusMm(pattern);
  // Distance from the spot's centre to the card square.
  const double gx = std::max(std::abs(c.x()) - half, 0.0);
  const double gy = std::max(std::abs(c.y()) - half, 0.0);
  return gx * gx + gy * gy <= r * r;
}

void patternSpots(const PatternGeometry& pattern, const TargetGeometry& target,
                  std::vector<PatternSpot>& out) {
  out.clear();
  const int columns = std::max(pattern.columns, 1);
  const int rows = std::max(pattern.rows, 1);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      if (!patternSpotTouchesCard(pattern, target, i, j)) out.push_back({i, j, patternNodeMm(pattern, i, j)});
}

}  // namespace imagepro
