#include "core/pipeline/engine.h"

#include <algorithm>

#include "core/pipeline/engine_impl.h"
#include "core/pipeline/pose_frames.h"
#include "core/segmentation/reduce.h"

namespace imagepro {

namespace {

// The region about a single detection is searched at full size, the whole frame on its
// reduced image (coarse search). The guess pays while it holds at most twice that image's
// pixels (the whole frame's search also counts and reduces every pixel), or half the frame
// without it: measured on the bench's real scenes, a larger guess at 1920 x 1080 (a near
// target's) cost more than the whole frame's search (tracked 1,203 -> 373 frames/s).
bool guessPays(const cv::Rect& region, cv::Size frame, const BinarizationOptions& binarization) {
  const int k = binarization.coarse_search ? coarseFactor(frame.width) : 1;
  return static_cast<double>(region.area()) <= 2.0 * static_cast<double>(frame.area()) / std::max(4, k * k);
}

}  // namespace

Engine::Engine() : impl_(std::make_unique<Impl>()) {}
Engine::Engine(const Settings& settings) : Engine() { impl_->settings = settings; }
Engine::~Engine() = default;

void Engine::setSettings(const Settings& settings) {
  impl_->settings = settings;
  impl_->members_stale = true;
}
const Settings& Engine::settings() const { return impl_->settings; }
void Engine::resetTracking() {
  impl_->tracker.reset();
  impl_->last_pose.reset();
  impl_->forgetTracks();
}
const Frame& Engine::lastFrame() const { return impl_->frame; }
const cv::Mat& Engine::binaryImage() const { return regionBinary(impl_->chain); }
const EdgeList& Engine::edges() const { return impl_->chain.edges; }
const Paths& Engine::paths() const { return impl_->chain.paths; }

void Engine::process(const Frame& frame, FrameResult& out) {
  // Shallow copy: the image buffer is shared, not copied.
  impl_->frame = frame;
  impl_->run(out);
}

Status Engine::step(FrameSource& source, FrameResult& out) {
  const auto start = EngineClock::now();
  const Status grabbed = source.next(impl_->frame);
  const double grab_us = microsecondsSince(start);
  if (!ok(grabbed)) {
    out = FrameResult{};
    out.index = impl_->frame.index;
    out.name = impl_->frame.name;
    out.status = grabbed;
    out.set_of_targets = !impl_->settings.targets.empty();
    out.times[Stage::Grab] = grab_us;
    if (grabbed != Status::EndOfStream) {
      impl_->tracker.observeMiss();
      impl_->forgetTracks();
    }
    impl_->last_pose.reset();
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
  out.times = {};

  const cv::Mat& grey = frame.image;
  const bool valid = !grey.empty() && grey.type() == CV_8UC1;
  // Tracking time: the frame's timestamp, or its index for sources without a clock.
  if (valid)
    last_track_time = frame.timestamp_s > last_track_time ? frame.timestamp_s : static_cast<double>(frame.index);
  const double t = last_track_time;
  // Only a stream is tracked (thesis appendix A: camera and virtual input). Image files
  // carry their name and are separate stills: the last one says nothing about the next.
  const bool stream = frame.name.empty();
  if (!settings.targets.empty()) {
    runSet(out, stream && valid);
    // A frame's truth is the set's first member's (the Virtual source draws that one at the
    // scene's pose): beside another shown target it would be another target's pose.
    if (out.target_id != settings.targets.front().id) out.truth.reset();
    applyPoseFrames(settings.frames, out);
    return;
  }
  cv::Rect region;  // empty: the whole frame
  if (valid) {
    if (!stream) {
      tracker.reset();
      last_pose.reset();
    }
    // Below the ellipse stage nothing finds the target, so nothing tells where it went: the
    // whole frame is searched (a region kept from earlier frames would stay where the
    // target was last found, and miss it once it has moved out).
    if (stream && !reachesEllipse(o.level)) tracker.reset();
    if (stream) {
      const bool guess = tracker.fromOneDetection();
      const TargetGeometry& followed = geometryOf(settings.targets, last_target_id, settings.target);
      const auto estimated = tracker.estimate(o.tracking, settings.camera(), followed, t, grey.size());
      if (estimated && (!guess || guessPays(*estimated, grey.size(), o.binarization))) region = *estimated;
    }
  }
  const Pose* expected = last_pose ? &*last_pose : nullptr;
  runStageChain(settings, grey, region, TargetsToReconstruct::Best, chain, out, expected);
  if (!region.empty() && tracker.fromOneDetection() && missedTarget(out, TargetsToReconstruct::Best)) {
    // The region about a single detection was a guess (the target's motion is not known
    // yet) and it missed: the whole frame is searched in the same frame, so the guess
    // costs a region's search and never a frame without a pose. Its stage times add up.
    const auto guessed = out.times;
    runStageChain(settings, grey, cv::Rect(), TargetsToReconstruct::Best, chain, out, expected);
    for (Stage s : {Stage::Crop, Stage::Threshold, Stage::Edges, Stage::Connectivity, Stage::Ellipse,
                    Stage::Reconstruction})
      out.times[s] += guessed[s];
  }
  last_pose = out.pose;
  last_target_id = out.target_id;

  // The tracker learns from every frame whose ellipse stage ran, and from every failure.
  const auto start = EngineClock::now();
  if (ok(out.status) && stageRan(out, ApplicationLevel::Ellipse) && !out.detected_region.empty()) {
    tracker.observe(last_track_time, cv::Rect2d(out.detected_region), out.pose);
  } else if (!ok(out.status) || stageRan(out, ApplicationLevel::Ellipse)) {
    tracker.observeMiss();
  }
  out.times[Stage::Tracking] = microsecondsSince(start);
  applyPoseFrames(settings.frames, out);
}

}  // namespace imagepro
