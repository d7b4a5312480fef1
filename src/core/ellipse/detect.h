#pragma once
// Ellipse detection stage (thesis 2.6): decides which connected paths are ellipses and
// which of them is the image of the target's white disk.
//
//  * Direct fit (2.6.2): every path of at least min_path_pixels is fitted
//    (direct_fit.h) and accepted when its error is below the threshold of the accept
//    rule (E_rel of eq. 2.42, or the mean Sampson distance in pixels) and the path
//    traces the fitted ellipse (EllipseOptions::min_traced_fraction of the part inside
//    the image). A path cut by the image border is an open arc and is fitted as such
//    (thesis fig. 2.27).
//  * Bennett (2.6.1): a path is accepted by the decision rules on its own accumulator
//    (bennett.h); its ellipse parameters come from the direct fit of the same path.
//
// Target selection, beyond the thesis's "best ellipse": the target is a white disk with
// two dark spots, so among the accepted ellipses with a white interior the one that
// holds exactly two dark closed paths of the spots' size, one near the centre and the
// other at spot_offset / radius from it, is the target. With robust_fit on, every path
// that may hold spots but failed the plain fit (an occluder's straight edges in the
// contour, thesis fig. 2.28) is refitted by consensus, also when a target was found
// already (a second, occluded target makes the frame ambiguous): the six-point fit
// whose ellipse the path traces most (at most robust_iterations), refitted on its
// inliers, accepted when they trace robust_min_traced_fraction of the ellipse. When
// they trace less, the pixels of other white paths on the same ellipse join them (an
// occluder across the disk cuts its outline into several paths). Only paths whose plain
// fit gave an ellipse holding (grown by half) a pair of dark paths shaped like the
// spots, not a found target's, are refitted, so the common frame runs no consensus.
// Paths are fitted lazily: detectTarget fits only white paths with two spot-sized dark
// paths inside their bounding box, smallest box first, skipping a path whose box holds
// no spots but a found target's, and traces the contour only of an ellipse that holds
// the spots; detectEllipses fits every path. Two or more targets give AmbiguousTarget
// (all reported, in path order) unless report_all_targets. Without any target so far, one
// last try with robust_fit: from a pair of dark paths shaped like the spots, the
// rim's edge pixels are gathered from every path around them, gradient pointing inwards,
// and fitted by consensus; an occluder that joins the disk to the scene beyond the card
// leaves the rim no path of its own, only arcs of others, while the spots stay whole
// (targets_from_spots: the stage chain leaves it to some passes). Without any target, the
// thesis's rule picks the best ellipse (lowest error, or highest Bennett score),
// preferring ellipses that hold any dark path over plain disks, unless
// require_target_spots; its runners-up stay in the workspace.
#include <opencv2/core.hpp>

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/connectivity/paths.h"
#include "core/ellipse/bennett.h"
#include "core/ellipse/direct_fit.h"
#include "core/ellipse/ellipse.h"
#include "core/ellipse/ellipse_trace.h"
#include "core/settings/options.h"

namespace imagepro {

inline constexpr std::size_t kNoPath = std::numeric_limits<std::size_t>::max();

struct TargetDetection {
  Ellipse ellipse;
  Conic conic = Conic::Zero();
  std::size_t path_index = kNoPath;
  double fit_error = 0.0;     // E_rel (eq. 2.42) of the fit
  double sampson_px = 0.0;    // mean Sampson distance of the path (its inliers when robust)
  double traced = 0.0;        // fraction of the ellipse's perimeter traced by the path
  double bennett_score = 0.0, bennett_quality = 0.0, bennett_symmetry = 0.0;  // Bennett only
  cv::Rect bbox;              // of the path's pixels
  // Paths of the centre spot and the offset spot (kNoPath when not found).
  std::array<std::size_t, 2> spot_paths{kNoPath, kNoPath};
  // Their paths' boxes in the image (the spots and a pixel round them), when found: the
  // reconstruction's own spot search falls back on them (extractSpots).
  std::array<cv::Rect, 2> spot_boxes{};
  bool spots_found = false;
  // When found: the spots' distance in the frame where the rim is the unit circle, the
  // fraction of the radius at which the offset spot sits (target_set.h tells members by it).
  double spot_fraction = 0.0;
  bool robust = false;        // found by the consensus fit
};

// One path's summary, kept per frame in the workspace.
struct PathSummary {
  cv::Rect bbox;
  double cx = 0.0, cy = 0.0;  // centroid of the pixels
  double rms_radius = 0.0;    // root-mean-square distance of the pixels from the centroid
  double polarity = 0.0;      // < 0: gradients point inwards (white interior), > 0: dark interior
  Status fit_status = Status::TooFewPoints;
  EllipseFit fit;
  EllipseTrace trace;
  BennettResult bennett;
  bool fitted = false;     // fit attempted (paths are fitted only when needed)
  bool candidate = false;  // fitted and within the error limit, contour not traced yet
  bool accepted = false;
};

// A plain ellipse's place in the thesis's choice: holding a dark path first (lacks_dark
// false), then by key (E_rel, Sampson distance or minus Bennett's score), then path order.
struct RankedEllipse {
  bool lacks_dark = false;
  double key = 0.0;
  std::size_t path = kNoPath;
  auto operator<=>(const RankedEllipse&) const = default;
};

// How many runners-up of the thesis's choice detectTarget keeps (EllipseWorkspace::runners_up).
inline constexpr std::size_t kRunnersUp = 8;

// Directions about a pair of spots in which targetsFromSpots takes its nearest edge pixel.
inline constexpr int kSeedArcs = 64;

// A pair of dark paths that may be a target's spots (targetsFromSpots): other dark paths
// of their size round them, then how unequal they are (|log| of their sizes' ratio).
struct SpotPairCandidate {
  int others = 0;
  double unequal = 0.0;
  std::size_t a = kNoPath, b = kNoPath;
  auto operator<=>(const SpotPairCandidate&) const = default;
};

// Buffers reused from frame to frame.
struct EllipseWorkspace {
  std::vector<PathSummary> paths;
  BennettWorkspace bennett;
  std::vector<EdgePixel> inliers;
  std::vector<EdgePixel> gathered;           // edge pixels about a pair of spots (targetsFromSpots)
  std::vector<std::size_t> gathered_counts;  // per path: how many of them it gave
  std::vector<EdgePixel> seeds;              // the nearest of them in each direction
  std::vector<std::size_t> by_x;             // dark paths in order of their centroid's x
  std::vector<std::size_t> narrow_by_x, wide;  // all paths: narrow ones by their box's left edge
  std::vector<SpotPairCandidate> pairs;      // pairs of them that may be spots, likeliest first
  std::vector<std::size_t> dark;   // closed paths around dark regions: spot candidates
  std::vector<std::size_t> spots;
  std::vector<std::size_t> order;  // paths that may hold spots, smallest box first
  std::mt19937 rng;
  std::size_t consensus_fits = 0;  // consensus fits run by the last detectTarget
  std::vector<RankedEllipse> ranked;
  // When detectTarget found no target but chose the best plain ellipse: the next best, in
  // order (at most kRunnersUp), for a caller that can test them further.
  std::vector<TargetDetection> runners_up;
};

// Shape-only classification: every accepted path, in path order, into `out` (cleared
// first, capacity reused). NoTarget when none is accepted. `image` is the frame size
// (for the border-cut arcs; empty: no border).
Status detectEllipses(const EllipseOptions& options, const Paths& paths, cv::Size image,
                      EllipseWorkspace& ws, std::vector<TargetDetection>& out);

// The target (see above): `out` holds the target, or every target found (status Ok with
// report_all_targets, AmbiguousTarget otherwise). NoTarget when nothing qualifies.
Status detectTarget(const EllipseOptions& options, const TargetGeometry& target, const Paths& paths,
                    cv::Size image, EllipseWorkspace& ws, std::vector<TargetDetection>& out);

// Consensus fit of one path (used by detectTarget; exposed for tests): Ok when the
// refit traces min_traced of the observable ellipse and passes the accept rule on its
// inliers. `fit` and `trace` describe the refit on the inliers.
Status fitEllipseRobust(const EllipseOptions& options, std::span<const EdgePixel> path, cv::Size image,
                        EllipseWorkspace& ws, EllipseFit& fit, EllipseTrace& trace);

// Whether a view of the target can give `e`: an axis ratio a tilt of at most
// o.target_max_tilt_deg gives, its centre inside the image (when `image` is not empty).
// Target selection, with or without spots, takes only these, so a sliver along a table's
// edge or an arc of a ring centred off the frame is no target.
bool plausibleTargetView(const EllipseOptions& o, const Ellipse& e, cv::Size image);

// The accept rule of the direct fit on a fit and its trace.
bool fitAccepted(const EllipseOptions& options, const EllipseFit& fit, const EllipseTrace& trace,
                 double min_traced_fraction);

}  // namespace imagepro
