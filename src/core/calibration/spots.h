#pragma once
// The centres of the pattern's black spots as the camera sees them (thesis 4.6 step 5):
// the image is thresholded only to find the dark 8-connected components; each
// component's centre is then measured on the grey levels,
// as the centroid weighted by darkness (local white level minus grey) over the component
// grown by two pixels, so the anti-aliased and blurred rim contributes in proportion to
// how much of the spot it covers and the threshold does not move the centre.
// The white level is the median grey of the border of the component's box grown by
// kSpotClearancePx. Pixels of other components are never counted.
//
// The threshold is the pipeline's automatic one (thesis 2.3) moved to halfway between the
// mean grey levels of the two classes it separates: the minimum-error threshold settles
// close to the narrow white mode of a mostly white sheet, where the blurred gap between a
// small distant spot and its neighbour, or the card, falls below it and joins them.
// A Manual threshold is used as given.
//
// Only plausible spots are kept: at least kMinSpotAreaPx pixels, at most 1% of the image
// (the card, the background beyond the sheet and other large dark regions are not
// spots), not touching the image border (a cut spot has a wrong centre), and with nothing
// else dark within kSpotClearancePx of its box (its blurred rim would pull the centre: a
// spot at the sheet's edge, a spot next to the card or a blemish). The matching
// (matching.h) then asks each one to have about the area the pattern's geometry predicts.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/status.h"
#include "core/segmentation/histogram.h"
#include "core/settings/options.h"

namespace imagepro {

inline constexpr int kMinSpotAreaPx = 3;
// Nothing else dark may lie within this many pixels of a spot's box (the two-pixel weighing
// ring and one more); the white level is read on the border of the box grown by as much.
inline constexpr int kSpotClearancePx = 3;

struct ObservedSpot {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // image px as seen (distorted)
  int area_px = 0;                                    // of the thresholded component
};

struct SpotFinderWorkspace {
  Histogram histogram{};
  cv::Mat dark;    // 255 where grey <= threshold
  cv::Mat labels;  // CV_32S component labels
  cv::Mat stats;
  cv::Mat centroids;
  std::vector<unsigned char> border;  // grey levels on a box border, for the median
};

// EmptyFrame for an empty or non-CV_8UC1 image; the threshold's own error (e.g.
// ThresholdUndefined on a flat image) when no threshold exists. Ok with `out` possibly empty.
// `threshold` None is taken as AT-Mod (the pattern image always needs a threshold).
Status findPatternSpots(const cv::Mat& grey, const ThresholdOptions& threshold, SpotFinderWorkspace& ws,
                        std::vector<ObservedSpot>& out);
// The same with the spots cut from `segment` (e.g. the image with its uneven light divided
// out) and their centres weighed on `grey` as the camera saw it (same size): dividing by an
// estimate of the light bends each spot's rim profile where the estimate is off.
// `max_area_fraction`: the largest spot, as a fraction of the image (a grid photographed
// close up has dots of several percent).
Status findPatternSpots(const cv::Mat& segment, const cv::Mat& grey, const ThresholdOptions& threshold,
                        SpotFinderWorkspace& ws, std::vector<ObservedSpot>& out, double max_area_fraction = 0.01);

}  // namespace imagepro
