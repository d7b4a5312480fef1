#include "core/settings/target_set.h"

#include <algorithm>
#include <cmath>
#include <utility>

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

bool namesATarget(const std::vector<TargetSpec>& set, int id) {
  if (set.empty()) return id == kLoneTargetId;
  return std::any_of(set.begin(), set.end(), [&](const TargetSpec& t) { return t.id == id; });
}

std::string framesProblem(const PoseFramesOptions& frames, const std::vector<TargetSpec>& set) {
  auto check = [&](const std::string& key, int id) -> std::string {
    if (id < 0 || namesATarget(set, id)) return {};
    return "frames." + key + ": " + std::to_string(id) + " is not the id of a target in the settings" +
           (set.empty() ? " (without a \"targets\" set the one target is id 0)" : " (see \"targets\")");
  };
  for (const auto& [key, id] : {std::pair<std::string, int>{"reference_target", frames.reference_target},
                                {"shown_target", frames.shown_target},
                                {"measured_targets[0]", frames.measured_targets[0]},
                                {"measured_targets[1]", frames.measured_targets[1]}})
    if (std::string problem = check(key, id); !problem.empty()) return problem;
  if (frames.measured_targets[0] >= 0 && frames.measured_targets[0] == frames.measured_targets[1])
    return "frames.measured_targets: the two targets must differ (both are " +
           std::to_string(frames.measured_targets[0]) + ")";
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
