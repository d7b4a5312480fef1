#pragma once
// Spots too small, blurred or compressed to be cut from the disk at the crop's mid grey
// level (a spot 2-3 px across under a pixel of blur and JPEG never gets that dark) are
// looked for where the target's geometry puts them instead: the centre spot near the
// centre of the rim's ellipse, the offset spot on the image of the circle of radius
// spot_offset about the centre (the rim's ellipse scaled by spot_offset / radius about
// its centre: exact for the affine part of the projection, off by far less than a spot
// on a target small enough to need this). Each is the darkest point there, in 3 x 3 means,
// with paper round it (three quarters of the points of two circles 1.5 px beyond one and
// one and a half spot radii, those on the disk and clear of the other spot, brighter than
// the mid grey level: the hole of a ring or a dark patch is no spot), and darker than that
// paper by a fifth of the paper-to-card contrast; the box around it is measured by the
// spot search's own darkness-weighted centroid.
#include <opencv2/core.hpp>

#include <array>

#include "core/common/geometry.h"
#include "core/ellipse/ellipse.h"

namespace imagepro {

// The two spots' boxes in image pixels (centre spot first), each about twice the spot's
// expected image radius across, or false when the model finds no spot dark enough.
// `bright`, `dark`: the crop's disk and card grey levels.
bool spotBoxesByModel(const cv::Mat& grey, const Ellipse& detected, const TargetGeometry& target, double bright,
                      double dark, std::array<cv::Rect, 2>& boxes);

}  // namespace imagepro
