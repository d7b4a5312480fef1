#include "core/pipeline/stage_chain.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>

#include "core/segmentation/histogram.h"
#include "core/segmentation/image_buffer.h"
#include "core/segmentation/reduce.h"
#include "core/segmentation/threshold.h"
#include "core/pipeline/told_targets.h"
#include "core/settings/target_set.h"

namespace imagepro {

namespace {

using Clock = std::chrono::steady_clock;

double microsecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

bool reached(ApplicationLevel level, ApplicationLevel stage) {
  return static_cast<int>(level) >= static_cast<int>(stage);
}

cv::Point2f point(const Eigen::Vector2d& p) { return {static_cast<float>(p.x()), static_cast<float>(p.y())}; }

TargetSummary summary(const TargetDetection& d) {
  TargetSummary s;
  s.ellipse = d.ellipse;
  s.fit_error = d.fit_error;
  s.sampson_px = d.sampson_px;
  s.bennett_score = d.bennett_score;
  s.bennett_quality = d.bennett_quality;
  s.bennett_symmetry = d.bennett_symmetry;
  s.bbox = d.bbox;
  return s;
}

// Shows the features the pose was computed from (the last target reconstructed).
void keepDisplayFeatures(const ReconstructionResult& r, FrameResult& out) {
  out.rim_seen = r.rim_seen;
  const bool checked = ok(r.status) || r.status == Status::AmbiguousPose || r.status == Status::PoseInconsistent;
  out.spot_error_px = checked ? r.spot_error_px : -1.0;
  out.rim_error_px = checked ? r.rim_error_px : -1.0;
  out.contour_points.clear();
  for (const Eigen::Vector2d& p : r.contour) out.contour_points.push_back(point(p));
  out.spots = {point(r.spots.centre_spot), point(r.spots.offset_spot)};
}

// The same of one target among several (TargetsToReconstruct::Every).
void keepTargetFeatures(const ReconstructionResult& r, TargetSummary& t) {
  t.rim_seen = r.rim_seen;
  const bool checked = ok(r.status) || r.status == Status::AmbiguousPose || r.status == Status::PoseInconsistent;
  t.spot_error_px = checked ? r.spot_error_px : -1.0;
  t.rim_error_px = checked ? r.rim_error_px : -1.0;
  t.spots = {point(r.spots.centre_spot), point(r.spots.offset_spot)};
}

// Edges, connectivity and the ellipse stage's target selection (thesis 2.4-2.6) on the
// binary image in chain.binary, as far as the application level asks. Stage times add
// up over the passes of one frame.
void findTargets(const Settings& settings, const cv::Mat& grey, cv::Rect inside, TargetsToReconstruct which,
                 ConnectivityWorkspace& connectivity_ws, StageChain& chain, FrameResult& out, bool from_spots = true) {
  const PipelineOptions& o = settings.pipeline;
  out.targets.clear();
  out.detected_region = {};
  out.edge_pixels = 0;
  out.paths = 0;
  chain.edges.clear();
  chain.paths.clear();
  chain.detections.clear();

  auto start = Clock::now();
  out.reached = ApplicationLevel::Edges;
  out.status = detectEdges(o.edge_method, chain.binary, chain.edges, chain.edge_ws);
  // Edges of the searched region in full-image coordinates, so every later stage
  // and the display work in one frame of reference.
  const auto dx = static_cast<std::int16_t>(inside.x);
  const auto dy = static_cast<std::int16_t>(inside.y);
  if (dx != 0 || dy != 0)
    for (EdgePixel& p : chain.edges) {
      p.x = static_cast<std::int16_t>(p.x + dx);
      p.y = static_cast<std::int16_t>(p.y + dy);
    }
  out.edge_pixels = chain.edges.size();
  out.times[Stage::Edges] += microsecondsSince(start);
  if (!ok(out.status) || !reached(o.level, ApplicationLevel::Connectivity)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Connectivity;
  out.status = connectPaths(o.connectivity, chain.edges, grey.size(), chain.paths, connectivity_ws);
  out.paths = chain.paths.pathCount();
  out.times[Stage::Connectivity] += microsecondsSince(start);
  if (!ok(out.status) || !reached(o.level, ApplicationLevel::Ellipse)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Ellipse;
  EllipseOptions ellipse = o.ellipse;
  if (which == TargetsToReconstruct::Every) ellipse.report_all_targets = true;
  // A pass may leave the rim from the spots (detect.h) to the passes after it (runStageChain).
  ellipse.targets_from_spots = ellipse.targets_from_spots && from_spots;
  const TargetSearch search = targetSearch(settings.targets, settings.target, ellipse.target_spot_tolerance);
  ellipse.target_spot_tolerance = search.spot_tolerance;
  out.status = detectTarget(ellipse, search.geometry, chain.paths, grey.size(), chain.ellipse_ws, chain.detections);
  for (const TargetDetection& d : chain.detections) out.targets.push_back(summary(d));
  if (ok(out.status) && chain.detections.empty()) out.status = Status::NoTarget;
  if (ok(out.status)) out.detected_region = chain.detections.front().bbox;
  out.times[Stage::Ellipse] += microsecondsSince(start);
}

// What one pass reports beyond the chain's buffers.
struct PassOutcome {
  Status status = Status::Ok;
  ApplicationLevel reached = ApplicationLevel::Source;
  std::size_t edge_pixels = 0, paths = 0;
  cv::Rect detected_region;
  std::optional<Pose> pose;
  int target_id = -1;
};

PassOutcome outcome(const FrameResult& out) {
  return {out.status, out.reached, out.edge_pixels, out.paths, out.detected_region, out.pose, out.target_id};
}

// What a pass's reconstruction writes into the frame result: cleared at the frame's start
// and before every pass after the first, so a pass never reports another's features.
void clearPassFeatures(FrameResult& out) {
  out.pose.reset();
  out.target_id = -1;
  out.ambiguous_poses.reset();
  out.contour_points.clear();
  out.rim_seen = 0.0;
  out.spot_error_px = out.rim_error_px = -1.0;
  out.pose_in_reference.reset();
  out.pose_in_world.reset();
  out.measured_pair.reset();
}

// Back to an earlier pass's report; the features shown were the later pass's, so none.
void restore(const PassOutcome& pass, FrameResult& out) {
  clearPassFeatures(out);
  out.status = pass.status;
  out.reached = pass.reached;
  out.edge_pixels = pass.edge_pixels;
  out.paths = pass.paths;
  out.detected_region = pass.detected_region;
  out.pose = pass.pose;
  out.target_id = pass.target_id;
}

// The passes swap their buffers with the spare ones, so either set may next hold the
// busiest pass's: each vector is given the larger capacity of the two, and once the
// frames have been seen no pass allocates.
template <class T>
void sameCapacity(std::vector<T>& a, std::vector<T>& b) {
  const std::size_t capacity = std::max(a.capacity(), b.capacity());
  a.reserve(capacity);
  b.reserve(capacity);
}

void sameCapacities(StageChain& chain, FrameResult& out) {
  sameCapacity(chain.edges, chain.spare.edges);
  sameCapacity(chain.paths.pixels, chain.spare.paths.pixels);
  sameCapacity(chain.paths.starts, chain.spare.paths.starts);
  sameCapacity(chain.detections, chain.spare.detections);
  sameCapacity(out.targets, chain.spare.targets);
}

// Swaps the reported pass's buffers (and the targets it reported) with the spare ones.
void swapPasses(StageChain& chain, FrameResult& out) {
  std::swap(chain.binary, chain.spare.binary);
  std::swap(chain.edges, chain.spare.edges);
  std::swap(chain.paths, chain.spare.paths);
  std::swap(chain.detections, chain.spare.detections);
  std::swap(out.targets, chain.spare.targets);
  std::swap(chain.reported_factor, chain.spare.factor);
}

// The spots the detection stage found, for the reconstruction's spot search to fall back on.
const std::array<cv::Rect, 2>* detectedSpots(const TargetDetection& d) {
  return d.spots_found ? &d.spot_boxes : nullptr;
}

// A reconstruction that found a pose fitting the image: Ok, or AmbiguousPose (two poses
// that both fit).
bool givesAPose(Status s) { return s == Status::Ok || s == Status::AmbiguousPose; }

// Detection `d` reconstructed as the member of the settings' set it is (target_set.h),
// its result in chain.reconstruction and the member's id in `id` (-1: none). Without a set,
// as the settings' one target. With one, as the member that the detection's measured
// coding names (UnknownTarget when it names none but a target so coded fits the image), or, when the detection did not see the
// spots (the reconstruction's own search finds them), as the member whose pose fits the
// spots best. Either way the member's pose must fit the spots clearly better than any
// other member's (kClearlyOtherMember): a target printed between two members' codings
// fits both about as well, and is UnknownTarget rather than the nearer one.
constexpr double kClearlyOtherMember = 2.0;

Status reconstructDetection(const Settings& settings, const cv::Mat& grey, const TargetDetection& d, int threshold,
                            StageChain& chain, const Pose* expected, int& id) {
  ReconstructionConfig config = reconstructionConfig(settings);
  const std::vector<TargetSpec>& set = settings.targets;
  auto as = [&](std::size_t member) {
    config.target = set[member].geometry;
    return reconstructTarget(config, grey, d.ellipse, threshold, chain.reconstruction_ws, chain.reconstruction,
                             expected, detectedSpots(d));
  };
  id = -1;
  if (set.empty()) {
    const Status s = reconstructTarget(config, grey, d.ellipse, threshold, chain.reconstruction_ws,
                                       chain.reconstruction, expected, detectedSpots(d));
    if (givesAPose(s)) id = kLoneTargetId;
    return s;
  }
  int named = -1;
  if (d.spots_found) {
    named = memberCodedAs(set, d.spot_fraction);
    if (named < 0) {
      // A print of no member only when it is a target at all: its pose, as the target its
      // measured share describes, fits the image. A photograph's ring with two dark marks
      // in it is no target, and says why (SpotsNotFound, PoseInconsistent ...).
      config.target = set.front().geometry;
      config.target.spot_offset_mm = d.spot_fraction * config.target.radius_mm;
      const Status s = reconstructTarget(config, grey, d.ellipse, threshold, chain.reconstruction_ws,
                                         chain.reconstruction, expected, detectedSpots(d));
      return givesAPose(s) ? Status::UnknownTarget : s;
    }
  }
  // The member named and its neighbours in coding (the members a misread share would
  // name), or every member when the share was not measured: the best fit and the next.
  auto candidate = [&](std::size_t m) {
    if (named < 0 || static_cast<int>(m) == named) return true;
    const double c = codingFraction(set[static_cast<std::size_t>(named)].geometry);
    const double mine = codingFraction(set[m].geometry);
    for (std::size_t k = 0; k < set.size(); ++k) {  // a member between them: not a neighbour
      const double other = codingFraction(set[k].geometry);
      if (static_cast<int>(k) != named && k != m && (other - c) * (other - mine) < 0.0) return false;
    }
    return true;
  };
  int best = -1;
  double bestError = 0.0, nextError = std::numeric_limits<double>::infinity();
  Status first = Status::SpotsNotFound;
  bool tried = false;
  for (std::size_t m = 0; m < set.size(); ++m) {
    if (!candidate(m)) continue;
    const Status s = as(m);
    if (!tried) first = s;
    tried = true;
    if (!givesAPose(s)) continue;
    const double e = chain.reconstruction.spot_error_px;
    if (best < 0 || e < bestError) {
      nextError = best < 0 ? nextError : bestError;
      best = static_cast<int>(m);
      bestError = e;
    } else {
      nextError = std::min(nextError, e);
    }
  }
  if (best < 0) return named >= 0 ? as(static_cast<std::size_t>(named)) : first;
  if ((named >= 0 && best != named) || nextError < kClearlyOtherMember * std::max(bestError, 0.05))
    return Status::UnknownTarget;
  id = set[static_cast<std::size_t>(best)].id;
  return as(static_cast<std::size_t>(best));  // its result back in chain.reconstruction
}

// The reconstruction chain of thesis 5.2.2 for the target found (or every target found).
void reconstructTargets(const Settings& settings, const cv::Mat& grey, TargetsToReconstruct which, StageChain& chain,
                        FrameResult& out, const Pose* expected) {
  if (!reached(settings.pipeline.level, ApplicationLevel::Reconstruction)) return;
  const auto start = Clock::now();
  out.reached = ApplicationLevel::Reconstruction;
  const ReconstructionConfig config = reconstructionConfig(settings);
  out.lens_inverse = lensInverse(config);
  if (which == TargetsToReconstruct::Best) {
    out.status = reconstructDetection(settings, grey, chain.detections.front(), out.threshold, chain, expected,
                                      out.target_id);
    keepDisplayFeatures(chain.reconstruction, out);
    if (ok(out.status)) out.pose = chain.reconstruction.pose;
    if (out.status == Status::AmbiguousPose || (ok(out.status) && chain.reconstruction.halfway_pose))
      out.ambiguous_poses = chain.reconstruction.candidates.pose;
  } else {
    for (std::size_t i = 0; i < chain.detections.size(); ++i) {
      TargetSummary& target = out.targets[i];
      target.status = reconstructDetection(settings, grey, chain.detections[i], out.threshold, chain, nullptr,
                                           target.target_id);
      keepTargetFeatures(chain.reconstruction, target);
      if (!ok(target.status)) continue;
      target.pose = chain.reconstruction.pose;
      if (!out.pose) {
        out.pose = target.pose;
        out.target_id = target.target_id;
        keepDisplayFeatures(chain.reconstruction, out);
      }
    }
  }
  out.times[Stage::Reconstruction] += microsecondsSince(start);
}


// Several targets found (AmbiguousTarget) where one is wanted. A photograph's ring, eye or
// crumpled tissue with two dark marks inside can pass the ellipse stage's test of a target
// but not the reconstruction's (the spots' own search, the pose and its self-check). When
// exactly one detection gives a pose that fits the image (Ok, or AmbiguousPose: two poses
// that both fit), it is the target and goes first, and the frame goes on as found; two
// that fit are two targets, and the frame stays AmbiguousTarget.
bool keepTheOneThatReconstructs(const Settings& settings, const cv::Mat& grey, StageChain& chain, FrameResult& out,
                                const Pose* expected) {
  const auto start = Clock::now();
  std::size_t fitting = 0, kept = 0;
  for (std::size_t i = 0; i < chain.detections.size() && fitting < 2; ++i) {
    int id = -1;
    const Status s = reconstructDetection(settings, grey, chain.detections[i], out.threshold, chain, expected, id);
    if (givesAPose(s)) {
      ++fitting;
      kept = i;
    }
  }
  out.times[Stage::Reconstruction] += microsecondsSince(start);
  if (fitting != 1) return false;
  std::swap(chain.detections.front(), chain.detections[kept]);
  std::swap(out.targets.front(), out.targets[kept]);
  out.status = Status::Ok;
  out.detected_region = chain.detections.front().bbox;
  return true;
}

// No ellipse held the target's spots as the ellipse stage sees them (two dark closed paths),
// and the best plain ellipse gave no pose. Under motion blur a far target's spots can be too
// faint for the binary image yet not for the reconstruction's own spot search, while a
// photograph's ring, holding a dark path, is ranked first. The runners-up go through the
// reconstruction, best first; the first that gives a pose that fits (Ok or AmbiguousPose)
// becomes the detection, and the frame goes on as found.
bool tryRunnersUp(const Settings& settings, const cv::Mat& grey, StageChain& chain, FrameResult& out,
                  const Pose* expected) {
  const auto start = Clock::now();
  for (const TargetDetection& d : chain.ellipse_ws.runners_up) {
    int id = -1;
    const Status s = reconstructDetection(settings, grey, d, out.threshold, chain, expected, id);
    if (!givesAPose(s)) continue;
    chain.detections.front() = d;
    out.targets.front() = summary(d);
    out.detected_region = d.bbox;
    out.status = Status::Ok;
    out.times[Stage::Reconstruction] += microsecondsSince(start);
    return true;
  }
  out.times[Stage::Reconstruction] += microsecondsSince(start);
  return false;
}

// A tracked region's histogram is taken on every k-th row, at least this many pixels.
constexpr int kRegionHistogramPixels = 8192;

// The full-size coordinate of the centre of a reduced pixel's block: block x covers
// [k x, k x + k) of the region starting at `origin`.
double enlarged(double x, int k, int origin) { return origin + k * x + 0.5 * (k - 1); }

// A reduced pass's detections (and the targets reported from them) in full-image
// coordinates, so the reconstruction crops the frame itself.
void enlargeDetection(int k, cv::Point origin, TargetDetection& d) {
  d.ellipse.cx = enlarged(d.ellipse.cx, k, origin.x);
  d.ellipse.cy = enlarged(d.ellipse.cy, k, origin.y);
  d.ellipse.a *= k;
  d.ellipse.b *= k;
  d.conic = conicFromEllipse(d.ellipse);
  d.sampson_px *= k;
  auto enlargedBox = [&](const cv::Rect& r) {
    return cv::Rect(origin.x + k * r.x, origin.y + k * r.y, k * r.width, k * r.height);
  };
  d.bbox = enlargedBox(d.bbox);
  for (cv::Rect& box : d.spot_boxes) box = enlargedBox(box);
}

void enlargeDetections(int k, cv::Point origin, StageChain& chain, FrameResult& out) {
  out.targets.clear();
  for (TargetDetection& d : chain.detections) {
    enlargeDetection(k, origin, d);
    out.targets.push_back(summary(d));
  }
  for (TargetDetection& d : chain.ellipse_ws.runners_up) enlargeDetection(k, origin, d);
  if (ok(out.status) && !chain.detections.empty()) out.detected_region = chain.detections.front().bbox;
}

// The reported reduced pass's edges and paths in the frame, each at the pixel nearest its
// k x k block's centre (rounded up and left: the top-left pixel for k = 2).
void moveReportedEdges(cv::Rect inside, StageChain& chain) {
  const int k = chain.reported_factor;
  if (k <= 1) return;
  auto move = [&](EdgePixel& p) {
    p.x = static_cast<std::int16_t>(inside.x + k * p.x + (k - 1) / 2);
    p.y = static_cast<std::int16_t>(inside.y + k * p.y + (k - 1) / 2);
  };
  for (EdgePixel& p : chain.edges) move(p);
  for (EdgePixel& p : chain.paths.pixels) move(p);
}

// One pass of the chain: a binarization of the searched region or of its reduced image.
struct Pass {
  bool local = false;
  int factor = 1;
  int window_px = 0;  // a local pass's window; 0: the settings'
};

// The window of the last local pass, run on a miss when the settings leave the window to
// the image's size (window_px 0). Over a dark background a far target's card is brighter
// than the wide window's mean, and card and disk binarize as one white blob with no
// ellipse in it; a window about a far disk's size puts the black card below its mean.
// It is for acquiring a target: a whole frame searched right after a pose (`expected`,
// a tracked stream's miss) skips it, for its cost (a millisecond or more on a cluttered
// frame); a tracked region, small, keeps it.
constexpr int kNarrowWindowPx = 15;
// On a frame wider than 640 px a far disk is wider in pixels, and a 15 px window cuts its
// blurred spots into the card; so first a local pass with the narrow window at the frame's
// scale (a 43rd of its width: 29 px at 1280 x 720), then the 15 px one. On the webcam
// stills a dim disk (paper at 70-120) before a bright scene is darker than the wide
// window's mean and only a window about its size finds it (docs/benchmarks.md, *A
// narrow pass at the frame's scale*).
int scaledNarrowWindowPx(int frameWidth) { return std::max(kNarrowWindowPx, frameWidth / 43) | 1; }

// Whether a missed pass's report says more than another's: it got further through the
// stages, or as far at full size where the other was reduced.
bool saysMore(ApplicationLevel reached, int factor, ApplicationLevel other, int otherFactor) {
  if (reached != other) return static_cast<int>(reached) > static_cast<int>(other);
  return factor == 1 && otherFactor > 1;
}

// What one frame's search works on: the frame, the region searched in it, and whether
// that region is the whole frame (a search to acquire the target) or a tracked one.
struct Search {
  const cv::Mat& grey;
  cv::Rect inside;  // the searched region, clipped to the frame
  cv::Mat searched;  // a view of it into the frame, never a copy: another view may share it
  bool whole_frame;
  TargetsToReconstruct which;
  const Pose* expected;
  // Every target of the settings' set is sought: the passes go on until each member is
  // told, and gather what each tells (chain.told).
  bool collect;
};

// The frame result and the chain's buffers as a new frame finds them.
void startFrame(cv::Size imageSize, StageChain& chain, FrameResult& out) {
  out.status = Status::Ok;
  out.reached = ApplicationLevel::Source;
  out.image_size = imageSize;
  out.threshold = -1;
  out.edge_pixels = 0;
  out.paths = 0;
  out.targets.clear();
  out.set_of_targets = false;
  clearPassFeatures(out);
  out.detected_region = {};
  out.lens_inverse = LensInverse::None;
  for (Stage s : {Stage::Crop, Stage::Threshold, Stage::Edges, Stage::Connectivity, Stage::Ellipse, Stage::Reconstruction})
    out.times[s] = 0.0;
  chain.edges.clear();
  chain.paths.clear();
  chain.detections.clear();
  chain.reported_factor = 1;
  chain.region = {};
  sameCapacities(chain, out);
}

// The searched region's histogram, and its image reduced by the coarse factor when a
// reduced pass comes first; returns that factor (1: no reduced pass).
int measureRegion(const PipelineOptions& o, const Search& search, StageChain& chain, FrameResult& out) {
  const auto start = Clock::now();
  if (search.whole_frame) {
    computeHistogram(search.searched, out.histogram);
  } else {
    // A tracked region: its grey-level distribution, all its threshold depends on, is the
    // same on every k-th row, at least kRegionHistogramPixels pixels in all.
    estimateHistogramFromRows(search.searched, std::max(1, search.inside.area() / kRegionHistogramPixels),
                              out.histogram);
  }
  // Only a search that ends in a pose can tell a reduced pass's miss from the target's
  // absence; the stages' own views (detect, edges) keep the frame's size. A tracked
  // region is small already, and its changing size would change the reduced image's,
  // whose connectivity index would then be rebuilt on every frame.
  int k = o.binarization.coarse_search && (search.which == TargetsToReconstruct::Best || search.collect) &&
                  reached(o.level, ApplicationLevel::Reconstruction) && search.whole_frame
              ? coarseFactor(search.inside.width)
              : 1;
  if (k > 1) {
    reduceByBlockMean(search.searched, k, chain.reduced, chain.reduce_ws);
    if (chain.reduced.empty()) k = 1;  // a frame too flat to reduce (fewer rows than k)
  }
  out.times[Stage::Crop] = microsecondsSince(start);
  return k;
}

// The frame's threshold, found in every mode: the histogram's display shows it and a
// re-threshold of None binarizes the target's crop with it. Returns whether the passes
// follow: not when a global threshold failed, nor below the Edges level (where only the
// binary image is shown).
bool thresholdFrame(const PipelineOptions& o, const Search& search, StageChain& chain, FrameResult& out) {
  const auto start = Clock::now();
  out.reached = ApplicationLevel::Threshold;
  out.status = computeThreshold(o.threshold, out.histogram, out.threshold);
  const Binarization mode = o.binarization.mode;
  if (mode != Binarization::Local && !ok(out.status)) {
    out.times[Stage::Threshold] = microsecondsSince(start);
    return false;
  }
  out.status = Status::Ok;
  if (!reached(o.level, ApplicationLevel::Edges)) {
    if (mode == Binarization::Local) binarizeLocal(search.searched, o.binarization, chain.local_ws, chain.binary);
    else binarize(search.searched, out.threshold, chain.binary);
  }
  out.times[Stage::Threshold] = microsecondsSince(start);
  return reached(o.level, ApplicationLevel::Edges);
}

// The passes in order: reduced before full size, and with global-then-local the global
// threshold before the local one at each size (threshold cycling on a miss), then the
// narrow local windows (at the frame's scale, then 15 px) when the settings leave the
// window to the image.
struct PassPlan {
  std::array<Pass, 6> passes{};
  int count = 0;
};

PassPlan planPasses(const BinarizationOptions& b, int k, const Search& search) {
  PassPlan plan;
  for (const int factor : {k, 1}) {
    if (b.mode != Binarization::Local) plan.passes[plan.count++] = {false, factor};
    if (b.mode != Binarization::Global) plan.passes[plan.count++] = {true, factor};
    if (k == 1) break;
  }
  if (b.mode != Binarization::Global && b.window_px == 0 && (!search.whole_frame || search.expected == nullptr)) {
    const int scaled = scaledNarrowWindowPx(search.grey.cols);
    if (scaled > kNarrowWindowPx) plan.passes[plan.count++] = {true, 1, scaled};
    plan.passes[plan.count++] = {true, 1, kNarrowWindowPx};
  }
  return plan;
}

// One pass: binarize, find the target, reconstruct it, and on a miss let the ellipse
// stage's runners-up try.
void runPass(const Settings& settings, const Search& search, const Pass& pass, StageChain& chain, FrameResult& out) {
  const PipelineOptions& o = settings.pipeline;
  const TargetsToReconstruct which = search.which;
  const cv::Mat& image = pass.factor > 1 ? chain.reduced : search.searched;
  const cv::Rect passRegion = pass.factor > 1 ? cv::Rect(0, 0, image.cols, image.rows) : search.inside;
  const auto start = Clock::now();
  if (pass.local) {
    BinarizationOptions local = o.binarization;
    if (pass.window_px > 0) local.window_px = pass.window_px;
    binarizeLocal(image, local, chain.local_ws, chain.binary);
  } else {
    binarize(image, out.threshold, chain.binary);
  }
  out.times[Stage::Threshold] += microsecondsSince(start);
  chain.reported_factor = pass.factor;
  if (pass.factor > 1) {
    findTargets(settings, chain.reduced, passRegion, which, chain.reduced_connectivity_ws, chain, out, false);
    enlargeDetections(pass.factor, search.inside.tl(), chain, out);
  } else {
    // The rim from the spots (detect.h) only on the full-size local passes (a global
    // pass's miss is mostly light that the local pass after it mends, at a fraction of the
    // cost), and not on a whole frame searched right after a pose: as the narrow pass, it
    // is for acquiring a target, and a tracked stream's one miss would pay for it
    // (docs/benchmarks.md).
    const bool fromSpots = (pass.local || o.binarization.mode == Binarization::Global) &&
                           (!search.whole_frame || search.expected == nullptr);
    findTargets(settings, search.grey, passRegion, which, chain.connectivity_ws, chain, out, fromSpots);
  }
  if (out.status == Status::AmbiguousTarget && which == TargetsToReconstruct::Best &&
      reached(o.level, ApplicationLevel::Reconstruction))
    keepTheOneThatReconstructs(settings, search.grey, chain, out, search.expected);
  if (ok(out.status)) reconstructTargets(settings, search.grey, which, chain, out, search.expected);
  if (which == TargetsToReconstruct::Best && out.reached == ApplicationLevel::Reconstruction &&
      missedTarget(out, which) && !chain.detections.front().spots_found &&
      tryRunnersUp(settings, search.grey, chain, out, search.expected))
    reconstructTargets(settings, search.grey, which, chain, out, search.expected);
}

// Of the passes that missed, the one whose report says most, kept in the spare buffers.
struct BetterMiss {
  bool kept = false;
  PassOutcome outcome;

  // Before the next pass: keeps the pass just run when it says more than the one kept.
  void offer(StageChain& chain, FrameResult& out) {
    if (!kept || saysMore(out.reached, chain.reported_factor, outcome.reached, chain.spare.factor)) {
      outcome = imagepro::outcome(out);
      swapPasses(chain, out);
      kept = true;
    }
  }
  // After the last pass missed too: the report of the one that said most.
  void report(StageChain& chain, FrameResult& out) const {
    if (kept && !saysMore(out.reached, chain.reported_factor, outcome.reached, chain.spare.factor)) {
      swapPasses(chain, out);
      restore(outcome, out);
    }
  }
};

// A set's targets told by the frame's passes become its targets (runStageChain).
void reportTold(const Settings& settings, StageChain& chain, FrameResult& out) {
  if (!chain.told.empty()) {  // else the report of the pass that said most
    sortInSetOrder(chain.told, settings.targets);
    std::swap(out.targets, chain.told);
    chain.told.clear();
  }
  adoptShownTarget(settings, out);
}

}  // namespace

void adoptShownTarget(const Settings& settings, FrameResult& out) {
  out.set_of_targets = true;
  const int shown = shownTarget(out.targets, settings.targets, settings.frames.shown_target);
  clearPassFeatures(out);
  if (shown < 0) {
    // Nothing told: the search's failure, or, when its stages all ran (several detections,
    // each reconstructed), the first detection's.
    if (ok(out.status)) out.status = out.targets.empty() ? Status::NoTarget : out.targets.front().status;
    return;
  }
  const TargetSummary& t = out.targets[static_cast<std::size_t>(shown)];
  out.status = t.status;
  if (ok(t.status)) out.pose = t.pose;
  out.target_id = t.status == Status::DuplicateTarget ? -1 : t.target_id;
  out.detected_region = t.bbox;
  out.rim_seen = t.rim_seen;
  out.spot_error_px = t.spot_error_px;
  out.rim_error_px = t.rim_error_px;
  out.spots = t.spots;
  // Of the targets told only the frame's status: Ok when any member has a pose.
  for (const TargetSummary& k : out.targets)
    if (ok(k.status)) out.status = Status::Ok;
}

bool missedTarget(const FrameResult& out, TargetsToReconstruct which) {
  if (out.status == Status::AmbiguousTarget || out.status == Status::AmbiguousPose) return false;
  if (!ok(out.status)) return true;
  return which == TargetsToReconstruct::Every && out.reached == ApplicationLevel::Reconstruction && !out.pose;
}

// Thesis figure 5.1: the searched region's histogram and threshold, then passes of
// binarization, edges, connectivity, ellipse and reconstruction until one finds the target.
void runStageChain(const Settings& settings, const cv::Mat& grey, cv::Rect region, TargetsToReconstruct which,
                   StageChain& chain, FrameResult& out, const Pose* expected) {
  const PipelineOptions& o = settings.pipeline;
  startFrame(grey.size(), chain, out);
  if (grey.empty() || grey.type() != CV_8UC1) {
    out.status = Status::EmptyFrame;
    out.search_region = {};
    return;
  }
  const cv::Rect whole(0, 0, grey.cols, grey.rows);
  out.search_region = region.empty() ? whole : region;
  const cv::Rect inside = out.search_region & whole;
  const bool collect = which == TargetsToReconstruct::Every && !settings.targets.empty();
  const Search search{grey, inside, grey(inside), inside == whole, which, expected, collect};
  chain.told.clear();

  const int k = measureRegion(o, search, chain, out);
  if (!reached(o.level, ApplicationLevel::Threshold) || !thresholdFrame(o, search, chain, out)) return;

  const PassPlan plan = planPasses(o.binarization, k, search);
  BetterMiss miss;
  for (int i = 0; i < plan.count; ++i) {
    if (i > 0) {
      miss.offer(chain, out);
      clearPassFeatures(out);
    }
    runPass(settings, search, plan.passes[i], chain, out);
    if (collect) {
      for (const TargetSummary& t : out.targets)
        if (isToldTarget(t)) addToldTarget(chain.told, t);
      if (everyMemberTold(chain.told, settings.targets)) break;
    } else if (!missedTarget(out, which)) {
      break;
    }
    if (i + 1 == plan.count) miss.report(chain, out);
  }
  if (collect) reportTold(settings, chain, out);
  moveReportedEdges(inside, chain);
  chain.region = inside;
}

const cv::Mat& regionBinary(StageChain& chain) {
  const int k = chain.reported_factor;
  if (k <= 1 || chain.binary.empty()) return chain.binary;
  cv::Mat& enlarged = chain.enlarged_binary;
  reuseBuffer(enlarged, chain.region.size(), allocationSize(enlarged));
  // Row by row (cv::Mat::setTo allocates on every call); white where no whole block reached.
  for (int y = 0; y < enlarged.rows; ++y) {
    std::uint8_t* dst = enlarged.ptr<std::uint8_t>(y);
    const int from = y / k;
    int filled = 0;
    if (from < chain.binary.rows) {
      const std::uint8_t* src = chain.binary.ptr<std::uint8_t>(from);
      filled = std::min(chain.binary.cols * k, enlarged.cols);
      for (int x = 0; x < filled; ++x) dst[x] = src[x / k];
    }
    std::fill(dst + filled, dst + enlarged.cols, std::uint8_t{255});
  }
  return enlarged;
}

}  // namespace imagepro
