#pragma once
// The rim edge model: the sub-pixel rim's points re-placed with what the whole rim shows,
// instead of what each crossing's few pixels show (docs/reconstruction.md, Rim edge model).
//
// Each crossing first found its edge between two plateaus of its own, two pixels each
// side. Those plateaus carry the pixels' noise into the point (the area estimate scales it
// by its window's 9 pixels), and on a small or oblique target the outer one can reach past
// the card into the scene. The model instead
//  1. fits the dark and the bright level over the whole rim, each a plane in the image
//     (light falling off across the target), from probes 2-3 px either side of every
//     crossing, leaving out probes that stray from the plane (a spot, the scene beyond the
//     card);
//  2. estimates the blur as a covariance S (motion blur spreads along one direction) from
//     the profile's steepest rise at the crossings, each giving the spread across the edge,
//     n' S n;
//  then leaves out every crossing whose own plateaus stray from the planes by over 35 % of
//  the contrast: beside a clamp or tape lying over the card, or a glare on the paper, the
//  crossing is not the paper-to-card edge, and the planes' mid-level would place it off
//  the rim;
//  3. places every point again on its own row or column: where the profile crosses the
//     planes' mid-level, or where the edge is sharp across (below 0.8 px, where linear
//     interpolation between two pixels errs) by the area under the profile over a window
//     of about +-2.5 spreads;
//  4. moves every point out by t' S t / (2 rho), t the rim's tangent and rho its radius of
//     curvature there: blur carries light round a curved edge, which moves its mid-level
//     towards the centre of curvature by that much, shrinks a small rim and flattens a
//     tilted one's sharply curved ends.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "core/ellipse/ellipse.h"
#include "core/reconstruction/features.h"

namespace imagepro {

struct RimEdgeFit {
  bool fitted = false;  // false: too few usable crossings; the points were left as found
  double dark = 0.0, bright = 0.0;  // the planes' levels at the rim's centre
  Eigen::Matrix2d blur_covariance = Eigen::Matrix2d::Zero();  // px^2
  double blur_sigma_px = 0.0;  // sqrt(trace / 2): the spread of an isotropic blur
  int moved = 0;     // points re-placed (the rest kept their first position)
  int left_out = 0;  // points beside an occluder or a glare, removed from `points`
};

// Re-places `points` (one per `ws.rim_crossings` entry, in order) on the grey frame, and
// removes from both those beside an occluder or a glare.
RimEdgeFit modelRimEdge(const cv::Mat& grey, const Ellipse& detected, FeatureWorkspace& ws,
                        std::vector<Eigen::Vector2d>& points);

}  // namespace imagepro
