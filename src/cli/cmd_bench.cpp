// imagepro-cli bench: frames per second of the whole engine on a realistic virtual
// sequence, with tracking off and on, per-stage times, peak memory and heap
// allocations per frame — and, on the very same frames in the same run, two peers:
// a pipeline composed of stock OpenCV calls and AprilTag 3 (tag36h11).
#include <sys/resource.h>

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "cli/allocation_counter.h"
#include "cli/bench_camera.h"
#include "cli/command.h"
#include "cli/peers/apriltag_peer.h"
#include "cli/peers/opencv_peer.h"
#include "core/pipeline/engine.h"
#include "core/source/bench_scene.h"

namespace imagepro::cli {
namespace {

using Clock = std::chrono::steady_clock;

struct Sequence {
  Settings settings;
  std::vector<Frame> target_frames;  // our target
  std::vector<Frame> tag_frames;     // the same scenes with an AprilTag over the target
};

Sequence makeSequence(cv::Size size, int frames) {
  Sequence seq;
  seq.settings = benchSceneSettings(size);
  const Settings& s = seq.settings;
  AprilTagPeer tags(s.camera, 2.0 * s.target.radius_mm);
  for (int i = 0; i < frames; ++i) {
    Frame f = renderCleanBenchFrame(s, i);
    Frame g = f;
    g.image = f.image.clone();
    tags.drawTag(*f.truth, g.image);
    degradeBenchFrame(f.image, kBenchBlurSigmaPx, kBenchNoiseSigma, static_cast<unsigned>(i));
    degradeBenchFrame(g.image, kBenchBlurSigmaPx, kBenchNoiseSigma, static_cast<unsigned>(i));
    seq.target_frames.push_back(std::move(f));
    seq.tag_frames.push_back(std::move(g));
  }
  return seq;
}

struct Run {
  double hz = 0.0;
  int found = 0;
  int frames = 0;
  double mean_position_error_mm = 0.0;
  std::uint64_t allocations = 0;
  std::vector<StageTimes> times;
  double mean_region_fraction = 1.0;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5));
  return v[k];
}

void notePose(Run& run, const std::optional<Pose>& truth, const Pose& pose) {
  ++run.found;
  if (truth) run.mean_position_error_mm += (translation(*truth) - translation(pose)).norm();
}

void finish(Run& run, double seconds) {
  run.hz = run.frames / std::max(seconds, 1e-12);
  if (run.found > 0) run.mean_position_error_mm /= run.found;
}

Run runEngine(const Sequence& seq, TrackingMode tracking) {
  Settings s = seq.settings;
  s.pipeline.tracking.mode = tracking;
  Engine engine(s);
  FrameResult r;
  // A first pass grows every buffer to its working size.
  for (const Frame& f : seq.target_frames) engine.process(f, r);
  engine.resetTracking();
  Run run;
  run.frames = static_cast<int>(seq.target_frames.size());
  run.times.reserve(seq.target_frames.size());
  double area = 0.0;
  const auto start = Clock::now();
  startCountingAllocations();
  for (const Frame& f : seq.target_frames) {
    engine.process(f, r);
    if (ok(r.status) && r.pose) notePose(run, f.truth, *r.pose);
    run.times.push_back(r.times);
    area += static_cast<double>(r.search_region.area()) / (f.image.cols * f.image.rows);
  }
  run.allocations = stopCountingAllocations();
  finish(run, std::chrono::duration<double>(Clock::now() - start).count());
  // The reservations above happen before counting; push_back within capacity is free.
  run.mean_region_fraction = area / std::max(1, run.frames);
  return run;
}

Run runOpenCvPeer(const Sequence& seq) {
  OpenCvPeerWorkspace ws;
  Pose pose;
  for (const Frame& f : seq.target_frames) opencvPeerPose(f.image, seq.settings.camera, seq.settings.target, ws, pose);
  Run run;
  run.frames = static_cast<int>(seq.target_frames.size());
  const auto start = Clock::now();
  startCountingAllocations();
  for (const Frame& f : seq.target_frames)
    if (ok(opencvPeerPose(f.image, seq.settings.camera, seq.settings.target, ws, pose))) notePose(run, f.truth, pose);
  run.allocations = stopCountingAllocations();
  finish(run, std::chrono::duration<double>(Clock::now() - start).count());
  return run;
}

Run runAprilTag(const Sequence& seq) {
  AprilTagPeer peer(seq.settings.camera, 2.0 * seq.settings.target.radius_mm);
  Pose pose;
  Run run;
  run.frames = static_cast<int>(seq.tag_frames.size());
  const auto start = Clock::now();
  startCountingAllocations();
  for (const Frame& f : seq.tag_frames)
    if (ok(peer.detect(f.image, pose))) notePose(run, f.truth, pose);
  run.allocations = stopCountingAllocations();
  finish(run, std::chrono::duration<double>(Clock::now() - start).count());
  return run;
}

long peakMemoryKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

struct ResolutionResult {
  cv::Size size;
  Run full, tracked, opencv, apriltag;
};

void printText(const ResolutionResult& r) {
  std::printf("\n== %dx%d, %d frames (grey, blur 0.8 px, noise 3, 8 clutter objects, moving target)\n",
              r.size.width, r.size.height, r.full.frames);
  std::printf("%-26s %12s %10s %14s %16s\n", "pipeline", "frames/s", "found", "mean |dT| mm", "allocs/frame");
  auto row = [](const char* name, const Run& run) {
    std::printf("%-26s %12.0f %6d/%-4d %14.2f %16.2f\n", name, run.hz, run.found, run.frames,
                run.mean_position_error_mm, static_cast<double>(run.allocations) / std::max(1, run.frames));
  };
  row("ImagePro full frame", r.full);
  row("ImagePro tracked", r.tracked);
  row("OpenCV composed pipeline", r.opencv);
  row("AprilTag 3 (tag36h11)", r.apriltag);
  std::printf("ratios: full/OpenCV %.1fx, full/AprilTag %.1fx, tracked/OpenCV %.1fx, tracked/AprilTag %.1fx\n",
              r.full.hz / r.opencv.hz, r.full.hz / r.apriltag.hz, r.tracked.hz / r.opencv.hz,
              r.tracked.hz / r.apriltag.hz);
  std::printf("tracked: mean searched region %.1f%% of the frame\n", 100.0 * r.tracked.mean_region_fraction);
  std::printf("\nper-stage us (full frame / tracked)      median         p99\n");
  for (std::size_t s = 0; s < kStageCount; ++s) {
    const auto stage = static_cast<Stage>(s);
    if (stage == Stage::Grab) continue;
    std::vector<double> a, b;
    for (const auto& t : r.full.times) a.push_back(t[stage]);
    for (const auto& t : r.tracked.times) b.push_back(t[stage]);
    std::printf("  %-16s %9.1f / %-9.1f %9.1f / %-9.1f\n", stageName(stage), percentile(a, 0.5), percentile(b, 0.5),
                percentile(a, 0.99), percentile(b, 0.99));
  }
}

std::string jsonResolution(const ResolutionResult& r) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "{\"width\": %d, \"height\": %d, \"frames\": %d, \"full_frame_hz\": %.1f, \"tracked_hz\": %.1f, "
                "\"opencv_pipeline_hz\": %.1f, \"apriltag_hz\": %.1f, \"full_frame_found\": %d, \"tracked_found\": %d, "
                "\"opencv_found\": %d, \"apriltag_found\": %d, \"full_frame_allocations_per_frame\": %.3f, "
                "\"tracked_allocations_per_frame\": %.3f, \"tracked_region_fraction\": %.4f}",
                r.size.width, r.size.height, r.full.frames, r.full.hz, r.tracked.hz, r.opencv.hz, r.apriltag.hz,
                r.full.found, r.tracked.found, r.opencv.found, r.apriltag.found,
                static_cast<double>(r.full.allocations) / std::max(1, r.full.frames),
                static_cast<double>(r.tracked.allocations) / std::max(1, r.tracked.frames),
                r.tracked.mean_region_fraction);
  return buf;
}

int run(const Args& args) {
  if (args.has("camera")) return runCameraBench(args);
  args.rejectUnknown({"frames", "resolution", "format"});
  const int frames = args.integer("frames", 200);
  if (frames < 10) throw UsageError("--frames must be at least 10");
  const std::string format = args.valueOr("format", "text");
  if (format != "text" && format != "json") throw UsageError("--format must be text or json");
  const std::string resolution = args.valueOr("resolution", "640x480");
  std::vector<cv::Size> sizes;
  if (resolution == "all") {
    sizes = {{640, 480}, {1280, 720}, {1920, 1080}};
  } else {
    int w = 0, h = 0;
    if (std::sscanf(resolution.c_str(), "%dx%d", &w, &h) != 2 || w < 160 || h < 120 || w > 8192 || h > 8192)
      throw UsageError("--resolution must be WxH (e.g. 1280x720) or all");
    sizes = {{w, h}};
  }

  // One core for everybody: OpenCV would otherwise spread its peer's work over threads.
  cv::setNumThreads(1);
  std::vector<ResolutionResult> results;
  for (const cv::Size& size : sizes) {
    std::fprintf(stderr, "rendering %d frames at %dx%d ...\n", frames, size.width, size.height);
    const Sequence seq = makeSequence(size, frames);
    ResolutionResult r;
    r.size = size;
    std::fprintf(stderr, "timing ImagePro (full frame, tracked), OpenCV pipeline, AprilTag ...\n");
    r.full = runEngine(seq, TrackingMode::Off);
    r.tracked = runEngine(seq, TrackingMode::Corners2D);
    r.opencv = runOpenCvPeer(seq);
    r.apriltag = runAprilTag(seq);
    if (format == "text") printText(r);
    results.push_back(std::move(r));
  }
  if (format == "json") {
    const ResolutionResult& first = results.front();
    std::printf("{\"full_frame_hz\": %.1f, \"tracked_hz\": %.1f, \"opencv_pipeline_hz\": %.1f, \"apriltag_hz\": %.1f, "
                "\"peak_memory_kb\": %ld, \"resolutions\": [",
                first.full.hz, first.tracked.hz, first.opencv.hz, first.apriltag.hz, peakMemoryKb());
    for (std::size_t i = 0; i < results.size(); ++i)
      std::printf("%s%s", i ? ", " : "", jsonResolution(results[i]).c_str());
    std::printf("]}\n");
  } else {
    std::printf("\npeak memory %.1f MB (including the pre-rendered frames)\n", peakMemoryKb() / 1024.0);
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "bench",
    "frames/s of the engine (tracking off and on) beside an OpenCV pipeline and AprilTag",
    "usage: imagepro-cli bench [--config FILE] [--frames N] [--resolution WxH|all] [--format text|json]\n\n"
    "Renders N realistic grey frames of a moving target (and the same scenes with an\n"
    "AprilTag tag36h11 as wide as the disk over the target), then times on one core:\n"
    "ImagePro's engine with tracking off and on, a pipeline of stock OpenCV calls\n"
    "(Otsu, findContours, fitEllipseDirect, solvePnP) and AprilTag 3 — same frames, same run.\n"
    "Prints frames/s, ratios, per-stage median and 99th-percentile microseconds, heap\n"
    "allocations per frame and peak memory. --resolution all also runs 1280x720 and 1920x1080.\n"
    "--format json prints one object with full_frame_hz, tracked_hz, opencv_pipeline_hz, apriltag_hz.\n\n"
    "usage: imagepro-cli bench --camera /dev/videoN [--size WxH] [--fps N] [--frames N] [--config FILE]\n"
    "                          [--format text|json]\n\n"
    "Times the engine on N frames (default 200) grabbed live from a V4L2 camera (size and rate\n"
    "as for reconstruct --camera, stored controls set): each frame is processed by an engine\n"
    "that tracks and by one that searches the whole frame. Prints the camera's rate by the\n"
    "driver's clock, dropped frames, each engine's median and 99th-percentile microseconds\n"
    "and frames/s, and whether the live loop is capture-limited or engine-limited.",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
