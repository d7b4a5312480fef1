#pragma once
// The dot grids a camera can be calibrated with (full intrinsics, intrinsics.h): the
// thesis's pattern (pattern.h) at any size, and OpenCV's two circle grids, with OpenCV's
// conventions so images taken for OpenCV work unchanged:
//  * the pattern size is points per row x rows (columns x rows here);
//  * symmetric grid: dot (row i, column j) at (j s, i s);
//  * asymmetric grid: dot (i, j) at ((2 j + i mod 2) s, i s), every row shifted by s
//    against the one before, so dots of one row are 2 s apart.
// The OpenCV grids carry no central target: their orientation comes from the grid itself
// (the asymmetric grid has one; the symmetric grid is the same turned by 180 deg, which
// changes each view's pose but not the intrinsics).
// Positions in mm on the sheet's plane (z = 0), +x right and +y down on the printed sheet.
#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/geometry.h"

namespace imagepro {

enum class DotGridKind : std::uint8_t { Thesis, SymmetricCircles, AsymmetricCircles };

// "thesis", "symmetric-circles", "asymmetric-circles" (the CLI's --pattern values).
std::string_view dotGridKindName(DotGridKind kind);
std::optional<DotGridKind> parseDotGridKind(std::string_view name);

struct DotGridSpec {
  DotGridKind kind = DotGridKind::AsymmetricCircles;
  int columns = 4;               // points per row (OpenCV's pattern width)
  int rows = 11;                 // rows (OpenCV's pattern height)
  double spacing_mm = 20.0;      // s
  double dot_diameter_mm = 0.0;  // 0: the default for the kind (defaultDotDiameterMm)
  // The thesis pattern's card and target (the other kinds have none).
  double card_size_mm = 130.0;
  TargetGeometry target;
};

// Half the spacing for the OpenCV grids (the nearest dots are s apart on the symmetric
// grid and s sqrt 2 on the asymmetric one), 0.32 s for the thesis pattern (its 8 mm spots
// 25 mm apart).
double defaultDotDiameterMm(const DotGridSpec& spec);
// The diameter used: the spec's, or the kind's default when it is 0.
double dotDiameterMm(const DotGridSpec& spec);

// Empty when the description can be drawn and found, else what is wrong with it, in words
// (rows below 2, a spacing not above 0, dots that touch their neighbours, ...).
std::string dotGridSpecError(const DotGridSpec& spec);

// The thesis pattern (pattern.h's geometry) of a Thesis spec.
PatternGeometry thesisPatternOf(const DotGridSpec& spec);

// Position of the dot in row `row`, column `column` (0-based). For the thesis pattern the
// target frame's node (pattern.h: centred on the target), for the OpenCV grids their
// convention above.
Eigen::Vector2d dotGridPointMm(const DotGridSpec& spec, int column, int row);

}  // namespace imagepro
