#include "core/pipeline/engine.h"

#include <chrono>

#include "core/connectivity/connectivity.h"
#include "core/edges/edges.h"
#include "core/pipeline/target_stage.h"
#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"
#include "core/tracking/tracker.h"

namespace imagepro {

namespace {

using Clock = std::chrono::steady_clock;

double microsecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

bool reached(ApplicationLevel level, ApplicationLevel stage) {
  return static_cast<int>(level) >= static_cast<int>(stage);
}

}  // namespace

struct Engine::Impl {
  Settings settings;
  RegionTracker tracker;
  Frame frame;
  cv::Mat binary;
  EdgeList edges;
  EdgeWorkspace edge_ws;
  Paths paths;
  ConnectivityWorkspace connectivity_ws;
  TargetStage target_stage;
  double last_track_time = -1.0;

  void run(FrameResult& out);
};

Engine::Engine() : impl_(std::make_unique<Impl>()) {}
Engine::Engine(const Settings& settings) : Engine() { impl_->settings = settings; }
Engine::~Engine() = default;

void Engine::setSettings(const Settings& settings) { impl_->settings = settings; }
const Settings& Engine::settings() const { return impl_->settings; }
void Engine::resetTracking() { impl_->tracker.reset(); }
const Frame& Engine::lastFrame() const { return impl_->frame; }
const cv::Mat& Engine::binaryImage() const { return impl_->binary; }
const EdgeList& Engine::edges() const { return impl_->edges; }
const Paths& Engine::paths() const { return impl_->paths; }

void Engine::process(const Frame& frame, FrameResult& out) {
  // Shallow copy: the image buffer is shared, not copied.
  impl_->frame = frame;
  impl_->run(out);
}

Status Engine::step(FrameSource& source, FrameResult& out) {
  const auto start = Clock::now();
  const Status grabbed = source.next(impl_->frame);
  const double grab_us = microsecondsSince(start);
  if (!ok(grabbed)) {
    out = FrameResult{};
    out.index = impl_->frame.index;
    out.name = impl_->frame.name;
    out.status = grabbed;
    out.times[Stage::Grab] = grab_us;
    if (grabbed != Status::EndOfStream) impl_->tracker.observeMiss();
    return grabbed;
  }
  impl_->run(out);
  out.times[Stage::Grab] = grab_us;
  return Status::Ok;
}

void Engine::Impl::run(FrameResult& out) {
  const PipelineOptions& o = settings.pipeline;
  out.index = frame.index;
  out.timestamp_s = frame.timestamp_s;
  out.name = frame.name;
  out.truth = frame.truth;
  out.status = Status::Ok;
  out.reached = ApplicationLevel::Source;
  out.image_size = frame.image.size();
  out.threshold = -1;
  out.edge_pixels = 0;
  out.paths = 0;
  out.targets.clear();
  out.pose.reset();
  out.detected_region = {};
  out.contour_points.clear();
  out.times = {};
  edges.clear();
  paths.clear();

  const cv::Mat& grey = frame.image;
  if (grey.empty() || grey.type() != CV_8UC1) {
    out.status = Status::EmptyFrame;
    out.search_region = {};
    tracker.observeMiss();
    return;
  }
  const cv::Rect whole(0, 0, grey.cols, grey.rows);

  // Tracking time: the frame's timestamp, or its index for sources without a clock.
  const double t = frame.timestamp_s > last_track_time ? frame.timestamp_s : static_cast<double>(frame.index);
  last_track_time = t;

  auto start = Clock::now();
  // Only a stream is tracked (thesis appendix A: camera and virtual input). Image files
  // carry their name and are separate stills: the last one says nothing about the next.
  const bool stream = frame.name.empty();
  if (!stream) tracker.reset();
  out.search_region =
      stream ? tracker.estimate(o.tracking, settings.camera, settings.target, t, grey.size()).value_or(whole) : whole;
  // The searched region is a view into the frame, not a copy: it is counted here and
  // binarized into the engine's own buffer (never the frame's: another view may share it).
  const cv::Mat searched = grey(out.search_region & whole);
  computeHistogram(searched, out.histogram);
  out.times[Stage::Crop] = microsecondsSince(start);
  if (!reached(o.level, ApplicationLevel::Threshold)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Threshold;
  out.status = computeThreshold(o.threshold, out.histogram, out.threshold);
  if (ok(out.status)) binarize(searched, out.threshold, binary);
  out.times[Stage::Threshold] = microsecondsSince(start);
  if (!ok(out.status)) {
    tracker.observeMiss();
    return;
  }
  if (!reached(o.level, ApplicationLevel::Edges)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Edges;
  out.status = detectEdges(o.edge_method, binary, edges, edge_ws);
  // Edges of the searched region in full-image coordinates, so every later stage
  // and the display work in one frame of reference.
  const auto dx = static_cast<std::int16_t>(out.search_region.x);
  const auto dy = static_cast<std::int16_t>(out.search_region.y);
  if (dx != 0 || dy != 0)
    for (EdgePixel& p : edges) {
      p.x = static_cast<std::int16_t>(p.x + dx);
      p.y = static_cast<std::int16_t>(p.y + dy);
    }
  out.edge_pixels = edges.size();
  out.times[Stage::Edges] = microsecondsSince(start);
  if (!ok(out.status)) {
    tracker.observeMiss();
    return;
  }
  if (!reached(o.level, ApplicationLevel::Connectivity)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Connectivity;
  out.status = connectPaths(o.connectivity, edges, grey.size(), paths, connectivity_ws);
  out.paths = paths.pathCount();
  out.times[Stage::Connectivity] = microsecondsSince(start);
  if (!ok(out.status)) {
    tracker.observeMiss();
    return;
  }
  if (!reached(o.level, ApplicationLevel::Ellipse)) return;

  // Ellipse detection and reconstruction (their own file: the target stage).
  target_stage.run(settings, grey, paths, out);

  start = Clock::now();
  if (ok(out.status) && !out.detected_region.empty()) {
    tracker.observe(t, cv::Rect2d(out.detected_region), out.pose);
  } else {
    tracker.observeMiss();
  }
  out.times[Stage::Tracking] = microsecondsSince(start);
}

}  // namespace imagepro
