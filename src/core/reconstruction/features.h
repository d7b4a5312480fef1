#pragma once
// Target features for the reconstruction (thesis 5.2.2: crop, re-segmentation, feature
// extraction): the smallest region holding the detected target plus a margin is cropped
// and re-thresholded on its own histogram (None, Manual, AT-Orig, AT-Mod, thesis fig. 2.8),
// then the rim's contour points and the two spots are taken from it. All positions are
// image pixels as seen (distorted); the distortion correction comes after.
// One file per step: crop.cpp (targetCrop, rethresholdCrop), contour.cpp (extractContour and
// its modes), spot_search.cpp (extractSpots).
//
// What each contour mode takes as the rim, why the MOD modes and the sub-pixel mode
// differ from ORG, and how the spots are cut and told from an occluder or glare:
// docs/reconstruction.md, sections "Contour modes", "Rim edge model" and "Spots".
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/ellipse/ellipse.h"
#include "core/segmentation/histogram.h"
#include "core/settings/options.h"

namespace imagepro {

struct SpotRun {
  int row = 0, x0 = 0, x1 = 0;  // crop coordinates, inclusive
  int parent = 0;               // union-find over runs
  bool at_limit = false;        // reaches the edge of the spot search's ellipse
};

struct SpotComponent {
  int area = 0, x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // crop coordinates, inclusive box
  bool at_limit = false;  // reaches the edge of the search: something from beyond the disk
};

// Where one sub-pixel rim point was found: on image row (or column) `line`, the inside of
// the rim towards `inwards` (+1 or -1) along it. The rim edge model re-places the point
// along that line.
struct RimCrossing {
  int line = 0;
  int inwards = 1;
  bool row = true;
};

struct FeatureWorkspace {
  Histogram histogram{};  // of the crop
  cv::Rect crop;          // the crop the threshold belongs to
  int threshold = -1;     // the crop's threshold
  double dark_mean = 0.0, bright_mean = 255.0;  // grey means of the classes [0, t], [t+1, 255]
  cv::Mat binary;         // the re-thresholded crop, 255 white, 0 black (modes other than SubPixel)
  cv::Mat visited;        // full path ORG: pixels already taken
  std::vector<SpotRun> runs;
  std::vector<int> runBounds;    // one row's dark runs, start and end in turn
  std::vector<int> componentOf;  // per root run: its component's index
  std::vector<SpotComponent> components;
  // The sub-pixel rim: each point's line, and the rim edge model's scratch (rim_edge.h).
  std::vector<RimCrossing> rim_crossings;
  std::vector<Eigen::Vector4d> rim_probes;  // x, y from the rim's centre; dark and bright level
  std::vector<double> rim_scratch, rim_residuals;
  std::vector<std::uint8_t> rim_keep;
  // The rim edge model's blur along its widest direction (px, the square root of the blur
  // covariance's larger eigenvalue: motion blur's length shows here); 0 without the model.
  double rim_blur_spread_px = 0.0;
};

struct SpotFeatures {
  Eigen::Vector2d centre_spot = Eigen::Vector2d::Zero();  // image px
  Eigen::Vector2d offset_spot = Eigen::Vector2d::Zero();
  int candidates = 0;  // components of spot size found
};

// The sub-pixel mode's crop histogram samples at least this many pixels (see rethresholdCrop).
constexpr int kCropHistogramPixels = 4096;

// Band half-width (px) about the detected ellipse in which MOD and SubPixel search the rim.
double contourBandPx(const Ellipse& detected);

// The crop: the detected ellipse's bounding box grown by `marginPx`, clipped to the image.
// OutOfImage when nothing of it is in the image.
Status targetCrop(const Ellipse& detected, int marginPx, cv::Size imageSize, cv::Rect& crop);

// The crop's threshold, from its own histogram (ThresholdUndefined on a flat crop), or with
// None the frame's own threshold `frameThreshold` (InvalidSettings when that is negative).
// The binary crop itself is made by extractContour for the modes that read it.
// `sampleRows`: a crop of at least 2 x kCropHistogramPixels pixels is histogrammed on every
// k-th row (at least kCropHistogramPixels pixels), for the sub-pixel mode, which takes only
// its class means and a starting point from the threshold; the pixel modes, whose points the
// threshold places, histogram the whole crop.
Status rethresholdCrop(const cv::Mat& grey, const cv::Rect& crop, const ThresholdOptions& rethreshold,
                       int frameThreshold, FeatureWorkspace& ws, int& threshold, bool sampleRows = false);

// Contour points of the rim (image px) by `mode` after rethresholdCrop: from the binary crop,
// or for SubPixel from the grey levels, then with `rimEdgeModel` re-placed by the rim edge
// model (ReconstructionOptions::rim_edge_model, rim_edge.h). TooFewPoints when fewer than 6
// are found.
Status extractContour(ContourMode mode, const cv::Mat& grey, const cv::Rect& crop,
                      const Ellipse& detected, FeatureWorkspace& ws,
                      std::vector<Eigen::Vector2d>& points, bool rimEdgeModel = true);

// The two spots (image px): SpotsNotFound with fewer than two, AmbiguousSpots with more.
// Their centres are darkness-weighted centroids, then with `weightedCentres` refined under
// a Gaussian window that follows the spot (ReconstructionOptions::weighted_spot_centres).
// When the crop's own cut finds no pair, or one only by taking a component that reaches
// the search's edge, `detectedSpots` (the detection stage's spot boxes, centre spot
// first), when given and inside the crop, are taken: the detection's
// local binary image parts a spot from an occluder that the crop's one cut level joins
// to it.
Status extractSpots(const cv::Mat& grey, const cv::Rect& crop, const Ellipse& detected,
                    const TargetGeometry& target, bool weightedCentres, FeatureWorkspace& ws,
                    SpotFeatures& spots, const std::array<cv::Rect, 2>* detectedSpots = nullptr);

}  // namespace imagepro
