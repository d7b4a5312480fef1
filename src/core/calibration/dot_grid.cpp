#include "core/calibration/dot_grid.h"

#include <cmath>

#include "core/calibration/pattern.h"

namespace imagepro {

std::string_view dotGridKindName(DotGridKind kind) {
  switch (kind) {
    case DotGridKind::Thesis: return "thesis";
    case DotGridKind::SymmetricCircles: return "symmetric-circles";
    case DotGridKind::AsymmetricCircles: return "asymmetric-circles";
  }
  return "?";
}

std::optional<DotGridKind> parseDotGridKind(std::string_view name) {
  for (const DotGridKind k : {DotGridKind::Thesis, DotGridKind::SymmetricCircles, DotGridKind::AsymmetricCircles})
    if (name == dotGridKindName(k)) return k;
  return std::nullopt;
}

double defaultDotDiameterMm(const DotGridSpec& spec) {
  return spec.kind == DotGridKind::Thesis ? 0.32 * spec.spacing_mm : 0.5 * spec.spacing_mm;
}

double dotDiameterMm(const DotGridSpec& spec) {
  return spec.dot_diameter_mm > 0.0 ? spec.dot_diameter_mm : defaultDotDiameterMm(spec);
}

std::string dotGridSpecError(const DotGridSpec& spec) {
  if (spec.columns < 2 || spec.rows < 2) return "a grid needs at least 2 columns and 2 rows";
  if (spec.columns > 500 || spec.rows > 500) return "at most 500 columns and 500 rows";
  if (!(spec.spacing_mm > 0.0) || !std::isfinite(spec.spacing_mm)) return "the spacing must be above 0 mm";
  if (!(spec.dot_diameter_mm >= 0.0) || !std::isfinite(spec.dot_diameter_mm))
    return "the dot diameter must be above 0 mm";
  const double d = dotDiameterMm(spec);
  // Nearest neighbours: s apart on the thesis and symmetric grids, s sqrt 2 on the asymmetric.
  const double nearest = spec.kind == DotGridKind::AsymmetricCircles ? spec.spacing_mm * std::sqrt(2.0) : spec.spacing_mm;
  if (d >= 0.8 * nearest) return "the dots must be smaller than 0.8 of their nearest neighbour's distance";
  if (spec.kind == DotGridKind::AsymmetricCircles && spec.rows < 3)
    return "an asymmetric grid needs at least 3 rows (OpenCV's finder)";
  if (spec.kind == DotGridKind::Thesis) {
    if (!(spec.card_size_mm > 2.0 * spec.target.radius_mm)) return "the card must be larger than the target's disk";
    if (!(spec.target.radius_mm > 0.0 && spec.target.spot_radius_mm > 0.0 && spec.target.spot_offset_mm > 0.0))
      return "the target's radius, spot radius and spot offset must be above 0 mm";
    if (spec.card_size_mm >= spec.spacing_mm * std::min(spec.columns, spec.rows))
      return "the card must leave grid spots around it (more columns and rows, or a smaller card)";
  }
  return {};
}

PatternGeometry thesisPatternOf(const DotGridSpec& spec) {
  PatternGeometry p;
  p.spot_spacing_mm = spec.spacing_mm;
  p.spot_radius_mm = 0.5 * dotDiameterMm(spec);
  p.columns = spec.columns;
  p.rows = spec.rows;
  p.card_size_mm = spec.card_size_mm;
  return p;
}

Eigen::Vector2d dotGridPointMm(const DotGridSpec& spec, int column, int row) {
  const double s = spec.spacing_mm;
  switch (spec.kind) {
    case DotGridKind::Thesis: return patternNodeMm(thesisPatternOf(spec), column, row);
    case DotGridKind::SymmetricCircles: return {column * s, row * s};
    case DotGridKind::AsymmetricCircles: return {(2 * column + row % 2) * s, row * s};
  }
  return Eigen::Vector2d::Zero();
}

}  // namespace imagepro
