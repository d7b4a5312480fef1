#include "core/settings/target_set.h"

#include <algorithm>
#include <cmath>

namespace imagepro {

namespace {

std::string named(const TargetSpec& t) {
  return "id " + std::to_string(t.id) + (t.name.empty() ? "" : " (" + t.name + ")");
}

}  // namespace

double codingFraction(const TargetGeometry& g) { return g.spot_offset_mm / g.radius_mm; }

std::string targetSetProblem(const std::vector<TargetSpec>& set) {
  for (std::size_t i = 0; i < set.size(); ++i) {
    const TargetGeometry& g = set[i].geometry;
    // The offset spot clear of the centre spot and inside the disk, a spot's width from both.
    if (g.spot_offset_mm < 3.0 * g.spot_radius_mm || g.spot_offset_mm > g.radius_mm - 2.0 * g.spot_radius_mm)
      return "targets[" + std::to_string(i) + "], " + named(set[i]) + ": its offset spot at " +
             std::to_string(g.spot_offset_mm) + " mm must lie between 3 spot radii from the centre and 2 from the rim";
    for (std::size_t j = 0; j < i; ++j) {
      if (set[j].id == set[i].id)
        return "targets[" + std::to_string(j) + "] and targets[" + std::to_string(i) + "] have the same id " +
               std::to_string(set[i].id);
      const double gap = std::abs(codingFraction(g) - codingFraction(set[j].geometry));
      if (gap < kMinCodingGap)
        return "targets[" + std::to_string(j) + "], " + named(set[j]) + ", and targets[" + std::to_string(i) + "], " +
               named(set[i]) + ", cannot be told apart: their offset spots sit at " +
               std::to_string(codingFraction(set[j].geometry)) + " and " + std::to_string(codingFraction(g)) +
               " of the radius, closer than " + std::to_string(kMinCodingGap);
    }
  }
  return {};
}

int memberCodedAs(const std::vector<TargetSpec>& set, double fraction) {
  for (std::size_t i = 0; i < set.size(); ++i)
    if (std::abs(codingFraction(set[i].geometry) - fraction) < 0.5 * kMinCodingGap) return static_cast<int>(i);
  return -1;
}

const TargetGeometry& geometryOf(const std::vector<TargetSpec>& set, int id, const TargetGeometry& lone) {
  for (const TargetSpec& t : set)
    if (t.id == id) return t.geometry;
  return lone;
}

TargetSearch targetSearch(const std::vector<TargetSpec>& set, const TargetGeometry& lone, double tolerance) {
  if (set.empty()) return {lone, tolerance};
  if (set.size() == 1) return {set.front().geometry, tolerance};
  double lo = 1e9, hi = -1e9, spot = 0.0;
  for (const TargetSpec& t : set) {
    lo = std::min(lo, codingFraction(t.geometry));
    hi = std::max(hi, codingFraction(t.geometry));
    spot += t.geometry.spot_radius_mm / t.geometry.radius_mm;
  }
  TargetGeometry g;
  g.radius_mm = 1.0;  // only ratios matter to the ellipse stage
  g.spot_radius_mm = spot / static_cast<double>(set.size());
  g.spot_offset_mm = 0.5 * (lo + hi);
  return {g, tolerance + 0.5 * (hi - lo)};
}

}  // namespace imagepro
