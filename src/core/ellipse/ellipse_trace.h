#pragma once
// The acceptance test's measure of a fitted ellipse (detect.h): how much of its perimeter
// the fitted points trace, how much of it the image can show, and their mean Sampson
// distance, in one pass over the points.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstddef>
#include <span>

#include "core/edges/edge_list.h"
#include "core/ellipse/direct_fit.h"

namespace imagepro {

// How completely a point set traces its fitted ellipse. The perimeter is cut into arcs
// of about 3 px; an arc is traced when a point within `inlier_px` (Sampson distance) of
// the ellipse lies on it, and observable when its middle lies inside the image.
struct EllipseTrace {
  double mean_sampson_px = 0.0;  // over all points
  double traced = 0.0;           // fraction of the perimeter traced
  double observable = 1.0;       // fraction of the perimeter inside the image
  std::size_t inliers = 0;       // points within inlier_px
};

// `image` empty: the whole perimeter counts as observable.
void traceEllipse(const EllipseFit& fit, std::span<const EdgePixel> points, double inlier_px,
                  cv::Size image, EllipseTrace& out);
void traceEllipse(const EllipseFit& fit, std::span<const Eigen::Vector2d> points, double inlier_px,
                  cv::Size image, EllipseTrace& out);

}  // namespace imagepro
