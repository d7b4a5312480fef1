#pragma once
// A set of printed targets in one scene (settings "targets"), each known by what is
// printed on it: its offset spot sits at its own fraction of the disk's radius (rf / R).
// That fraction is a ratio of lengths in the disk's plane, so it is measured without
// knowing the target's size: the ellipse stage reads it in the frame where the rim is the
// unit circle (TargetDetection::spot_fraction). Without a set the settings' one "target"
// is the lone member, id kLoneTargetId.
#include <string>
#include <vector>

#include "core/common/geometry.h"
#include "core/settings/options.h"

namespace imagepro {

struct TargetSpec {
  int id = 0;
  std::string name;  // for people; may be empty
  TargetGeometry geometry;
};

// The id of the settings' one target when no set is given.
inline constexpr int kLoneTargetId = 0;

// Two members' codings differ by at least this (a share of the radius). A wrong member's
// offset spot then lies 0.15 R from the one seen: 1.2 px on a 16 px rim (2.5 m from the
// thesis camera) seen at 60 deg, beyond the self-check's 1 px, and half of it, the
// margin left to a measured fraction, is twice the perspective's bias on it.
inline constexpr double kMinCodingGap = 0.15;

// rf / R: where the offset spot sits.
double codingFraction(const TargetGeometry& g);

// "" when the set can be told apart; else the problem naming the members: a duplicate id,
// two codings closer than kMinCodingGap, or an offset spot that touches the centre spot
// or the rim.
std::string targetSetProblem(const std::vector<TargetSpec>& set);

// Whether `id` names a target: a member of `set`, or kLoneTargetId without a set.
bool namesATarget(const std::vector<TargetSpec>& set, int id);

// "" when every id of `frames` (-1: none) names a target (namesATarget); else the
// problem naming the key and the id. Two measured targets must differ.
std::string framesProblem(const PoseFramesOptions& frames, const std::vector<TargetSpec>& set);

// The index of the member coded as `fraction` (within half kMinCodingGap), or -1.
int memberCodedAs(const std::vector<TargetSpec>& set, double fraction);

// The geometry of member `id`; `lone` when the set has no such member (or no set is given).
const TargetGeometry& geometryOf(const std::vector<TargetSpec>& set, int id, const TargetGeometry& lone);

// What the ellipse stage looks for when every member of `set` is to be found: the members'
// mean spot size and the middle of their codings, the spot tolerance widened by half
// their spread. A set of none or one is that one geometry and `tolerance` unchanged.
struct TargetSearch {
  TargetGeometry geometry;
  double spot_tolerance = 0.0;
};
TargetSearch targetSearch(const std::vector<TargetSpec>& set, const TargetGeometry& lone, double tolerance);

}  // namespace imagepro
