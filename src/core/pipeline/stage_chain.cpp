#include "core/pipeline/stage_chain.h"

#include <chrono>

#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"

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
  out.contour_points.clear();
  for (const Eigen::Vector2d& p : r.contour) out.contour_points.push_back(point(p));
  out.spots = {point(r.spots.centre_spot), point(r.spots.offset_spot)};
}

// Edges, connectivity and the ellipse stage's target selection (thesis 2.4-2.6) on the
// binary image in chain.binary, as far as the application level asks. Stage times add
// up over the passes of one frame.
void findTargets(const Settings& settings, const cv::Mat& grey, cv::Rect inside, TargetsToReconstruct which,
                 StageChain& chain, FrameResult& out) {
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
  out.status = connectPaths(o.connectivity, chain.edges, grey.size(), chain.paths, chain.connectivity_ws);
  out.paths = chain.paths.pathCount();
  out.times[Stage::Connectivity] += microsecondsSince(start);
  if (!ok(out.status) || !reached(o.level, ApplicationLevel::Ellipse)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Ellipse;
  EllipseOptions ellipse = o.ellipse;
  if (which == TargetsToReconstruct::Every) ellipse.report_all_targets = true;
  out.status = detectTarget(ellipse, settings.target, chain.paths, grey.size(), chain.ellipse_ws, chain.detections);
  for (const TargetDetection& d : chain.detections) out.targets.push_back(summary(d));
  if (ok(out.status) && chain.detections.empty()) out.status = Status::NoTarget;
  if (ok(out.status)) out.detected_region = chain.detections.front().bbox;
  out.times[Stage::Ellipse] += microsecondsSince(start);
}

// Whether a pass missed the target: a failure after the threshold was found (no edges, no
// target, a reconstruction that failed), or, with every target reconstructed, none that
// reconstructed. Two targets (AmbiguousTarget) or two poses (AmbiguousPose) are findings
// of the target, not misses.
bool missed(const FrameResult& out, TargetsToReconstruct which) {
  if (out.status == Status::AmbiguousTarget || out.status == Status::AmbiguousPose) return false;
  if (!ok(out.status)) return true;
  return which == TargetsToReconstruct::Every && out.reached == ApplicationLevel::Reconstruction && !out.pose;
}

// What one pass reports beyond the chain's buffers.
struct PassOutcome {
  Status status = Status::Ok;
  ApplicationLevel reached = ApplicationLevel::Source;
  std::size_t edge_pixels = 0, paths = 0;
  cv::Rect detected_region;
  std::optional<Pose> pose;
};

PassOutcome outcome(const FrameResult& out) {
  return {out.status, out.reached, out.edge_pixels, out.paths, out.detected_region, out.pose};
}

// Back to the first pass's report; the features shown were the second pass's, so none.
void restore(const PassOutcome& pass, FrameResult& out) {
  out.status = pass.status;
  out.reached = pass.reached;
  out.edge_pixels = pass.edge_pixels;
  out.paths = pass.paths;
  out.detected_region = pass.detected_region;
  out.pose = pass.pose;
  out.contour_points.clear();
}

// Swaps the reported pass's buffers (and the targets it reported) with the spare ones.
void swapPasses(StageChain& chain, FrameResult& out) {
  std::swap(chain.binary, chain.spare.binary);
  std::swap(chain.edges, chain.spare.edges);
  std::swap(chain.paths, chain.spare.paths);
  std::swap(chain.detections, chain.spare.detections);
  std::swap(out.targets, chain.spare.targets);
}

// The reconstruction chain of thesis 5.2.2 for the target found (or every target found).
void reconstructTargets(const Settings& settings, const cv::Mat& grey, TargetsToReconstruct which, StageChain& chain,
                        FrameResult& out, const Pose* expected) {
  if (!reached(settings.pipeline.level, ApplicationLevel::Reconstruction)) return;
  const auto start = Clock::now();
  out.reached = ApplicationLevel::Reconstruction;
  const ReconstructionConfig config = reconstructionConfig(settings);
  if (which == TargetsToReconstruct::Best) {
    out.status = reconstructTarget(config, grey, chain.detections.front().ellipse, out.threshold,
                                   chain.reconstruction_ws, chain.reconstruction, expected);
    keepDisplayFeatures(chain.reconstruction, out);
    if (ok(out.status)) out.pose = chain.reconstruction.pose;
    if (out.status == Status::AmbiguousPose) out.ambiguous_poses = chain.reconstruction.candidates.pose;
  } else {
    for (std::size_t i = 0; i < chain.detections.size(); ++i) {
      TargetSummary& target = out.targets[i];
      target.status = reconstructTarget(config, grey, chain.detections[i].ellipse, out.threshold,
                                        chain.reconstruction_ws, chain.reconstruction);
      if (!ok(target.status)) continue;
      target.pose = chain.reconstruction.pose;
      if (!out.pose) {
        out.pose = target.pose;
        keepDisplayFeatures(chain.reconstruction, out);
      }
    }
  }
  out.times[Stage::Reconstruction] += microsecondsSince(start);
}

}  // namespace

void runStageChain(const Settings& settings, const cv::Mat& grey, cv::Rect region, TargetsToReconstruct which,
                   StageChain& chain, FrameResult& out, const Pose* expected) {
  const PipelineOptions& o = settings.pipeline;
  out.status = Status::Ok;
  out.reached = ApplicationLevel::Source;
  out.image_size = grey.size();
  out.threshold = -1;
  out.edge_pixels = 0;
  out.paths = 0;
  out.targets.clear();
  out.pose.reset();
  out.ambiguous_poses.reset();
  out.detected_region = {};
  out.contour_points.clear();
  for (Stage s : {Stage::Crop, Stage::Threshold, Stage::Edges, Stage::Connectivity, Stage::Ellipse, Stage::Reconstruction})
    out.times[s] = 0.0;
  chain.edges.clear();
  chain.paths.clear();
  chain.detections.clear();

  if (grey.empty() || grey.type() != CV_8UC1) {
    out.status = Status::EmptyFrame;
    out.search_region = {};
    return;
  }
  const cv::Rect whole(0, 0, grey.cols, grey.rows);
  out.search_region = region.empty() ? whole : region;
  const cv::Rect inside = out.search_region & whole;

  auto start = Clock::now();
  // The searched region is a view into the frame, not a copy: it is counted here and
  // binarized into the chain's own buffer (never the frame's: another view may share it).
  const cv::Mat searched = grey(inside);
  computeHistogram(searched, out.histogram);
  out.times[Stage::Crop] = microsecondsSince(start);
  if (!reached(o.level, ApplicationLevel::Threshold)) return;

  // The frame's threshold is found in every mode: the histogram's display shows it and a
  // re-threshold of None binarizes the target's crop with it.
  start = Clock::now();
  out.reached = ApplicationLevel::Threshold;
  out.status = computeThreshold(o.threshold, out.histogram, out.threshold);
  const bool local_first = o.binarization.mode == Binarization::Local;
  if (local_first) {
    binarizeLocal(searched, o.binarization, chain.local_ws, chain.binary);
    out.status = Status::Ok;
  } else if (ok(out.status)) {
    binarize(searched, out.threshold, chain.binary);
  }
  out.times[Stage::Threshold] = microsecondsSince(start);
  if (!ok(out.status) || !reached(o.level, ApplicationLevel::Edges)) return;

  findTargets(settings, grey, inside, which, chain, out);
  if (ok(out.status)) reconstructTargets(settings, grey, which, chain, out, expected);
  if (o.binarization.mode == Binarization::GlobalThenLocal && missed(out, which)) {
    // Threshold cycling on a miss: the second pass, on the local binary image, into the
    // spare buffers.
    const PassOutcome first = outcome(out);
    swapPasses(chain, out);
    start = Clock::now();
    binarizeLocal(searched, o.binarization, chain.local_ws, chain.binary);
    out.times[Stage::Threshold] += microsecondsSince(start);
    out.pose.reset();
    out.ambiguous_poses.reset();
    findTargets(settings, grey, inside, which, chain, out);
    if (ok(out.status)) reconstructTargets(settings, grey, which, chain, out, expected);
    // Both missed: the report of the pass that got further (its status says more), the
    // first on a tie.
    if (missed(out, which) && static_cast<int>(out.reached) <= static_cast<int>(first.reached)) {
      swapPasses(chain, out);
      restore(first, out);
    }
  }
}

}  // namespace imagepro
