#pragma once
// The rim's ellipse from the points that lie on it. The direct fit (thesis 2.6.2)
// weighs every contour point alike, so an occluder lying across the rim (tape, a clamp, a
// finger) whose own edge falls inside the band where the rim is searched, or a glare that
// lifts the paper's level at a crossing, pulls the whole ellipse. fitRim fits every point,
// then keeps the points within max(kMinRimBandPx, kRimSigmas * the robust spread of all the
// points' distances) of that ellipse (Sampson distance) and fits them again, until the kept
// set stops changing (at most six rounds); a point left out in one round comes back in the
// next if the new fit passes near it. On a clean rim every point stays (the band is wider
// than the sub-pixel points' scatter), so the fit is the plain one, at the cost of one pass
// over the points' distances. The band's floor is a third of a pixel: the sub-pixel points
// of a blurred, noisy rim scatter by a tenth, and an occluder's edge within 0.6 px of a far
// rim (kept by a floor of 0.6 px) turned the pose of a target seen nearly along its axis to
// the wrong one of the rim's two circles (docs/reconstruction.md).
//
// The share of the rim seen: of kRimArcs equal arcs of the fitted ellipse (by the eccentric
// angle), those that hold a kept point; an occluded arc holds none (no crossing was found
// there, or its crossings were left out).
#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "core/common/status.h"
#include "core/ellipse/direct_fit.h"

namespace imagepro {

inline constexpr double kMinRimBandPx = 0.3;
inline constexpr double kRimSigmas = 3.0;
inline constexpr int kRimArcs = 32;

struct RimFitWorkspace {
  std::vector<Eigen::Vector2d> all_ideal, all_seen;  // every point, as given
  std::vector<std::uint8_t> keep;
  std::vector<double> residuals, scratch;
};

struct RimFit {
  EllipseFit fit;
  std::size_t kept = 0;  // points on the rim (the others were left out)
  double seen = 0.0;     // share of the rim's arcs holding a kept point, 0..1
};

// Fits the rim to `ideal` (distortion-corrected points) and leaves out of `ideal` and of
// `seen` (the same points as seen, in the same order) every point off the rim. TooFewPoints
// when fewer than 6 stay; the direct fit's status when it fails. With `robust` false, one
// plain fit of every point (ReconstructionOptions::robust_rim_fit).
Status fitRim(std::vector<Eigen::Vector2d>& ideal, std::vector<Eigen::Vector2d>& seen, bool robust,
              RimFitWorkspace& ws, RimFit& out);

// The share of kRimArcs equal arcs (by eccentric angle) of `e` that hold one of `points`.
double rimShareSeen(const Ellipse& e, const std::vector<Eigen::Vector2d>& points);

}  // namespace imagepro
