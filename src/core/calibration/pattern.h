#pragma once
// The calibration pattern of thesis 4.3 (fig. 4.6), as docs/conventions.md fixes it: a white
// sheet of columns x rows spot spacings, the secondary target on its black square card at
// the centre, and a grid of black spots spot_spacing_mm apart centred on the target,
// without every grid spot that would touch the card. The same description is drawn by
// the Virtual source (virtual_renderer.h) and by the printable documents
// (pattern_document.h); this file is the geometry both and the calibration share.
//
// Positions are in the target frame (mm, z = 0): origin at the disk's centre, +X towards
// the offset spot, +Y completing the frame (down on the printed sheet).
#include <Eigen/Core>

#include <vector>

#include "core/common/geometry.h"

namespace imagepro {

struct PatternSpot {
  int column = 0;  // 0 .. columns-1, left to right
  int row = 0;     // 0 .. rows-1, top to bottom
  Eigen::Vector2d position_mm = Eigen::Vector2d::Zero();
};

// Half the side of the black card; the card always carries the whole disk.
double patternCardHalfMm(const PatternGeometry& pattern, const TargetGeometry& target);
// Spot radius as drawn: at most half the spacing, so neighbouring spots never merge.
double patternSpotRadiusMm(const PatternGeometry& pattern);
// Width and height of the sheet: columns and rows spacings, centred on the target.
Eigen::Vector2d patternSheetSizeMm(const PatternGeometry& pattern);
// Position of grid node (column, row), whether or not a spot is drawn there.
Eigen::Vector2d patternNodeMm(const PatternGeometry& pattern, int column, int row);
// True when the spot of grid node (column, row) touches or overlaps the card (left out).
bool patternSpotTouchesCard(const PatternGeometry& pattern, const TargetGeometry& target,
                            int column, int row);

// Every drawn grid spot, row by row, left to right.
void patternSpots(const PatternGeometry& pattern, const TargetGeometry& target,
                  std::vector<PatternSpot>& out);

}  // namespace imagepro
