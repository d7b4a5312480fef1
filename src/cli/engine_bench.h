#pragma once
// The engine's throughput, timed on one core over pre-rendered frames, with tracking off
// and on: frames per second, poses found and their mean position error, per-stage times
// and heap allocations per frame. Two kinds of frames: the realistic virtual bench scene
// (core/source/bench_scene.h) and real scenes, the target over photographs
// (real_bench_scene.h; left out, said in one line, when there are no photographs). `imagepro-cli bench` reports it alone; `imagepro-studies
// bench-peers` times the peers on the very same frames in the same run and reports
// them in the same table.
#include <opencv2/core.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cli/allocation_counter.h"
#include "cli/command.h"
#include "core/common/frame.h"
#include "core/pipeline/frame_result.h"
#include "core/settings/settings.h"
#include "core/source/real_scene.h"

namespace imagepro::cli {

enum class BenchKind : std::uint8_t { Virtual, Real };

struct BenchSequence {
  BenchKind kind = BenchKind::Virtual;
  Settings settings;         // the bench scene's, for this frame size
  std::vector<Frame> frames;  // degraded, each with its true pose
  // Real scenes: frame `index` drawn again with `painter` in the target's place (a peer's
  // object at the same pose in the same conditions); false with `error` on a failure.
  std::function<bool(int index, const ScenePainter& painter, RealSceneFrame& out, std::string& error)> redraw;
};

struct BenchRun {
  double hz = 0.0;
  int found = 0;
  int frames = 0;
  double mean_position_error_mm = 0.0;
  std::uint64_t allocations = 0;
  std::vector<StageTimes> times;     // the engine's only
  double mean_region_fraction = 1.0;  // tracked: the searched share of the frame

  double allocationsPerFrame() const { return static_cast<double>(allocations) / std::max(1, frames); }
  // A pose found on a frame: counted, its position error summed.
  void notePose(const std::optional<Pose>& truth, const Pose& pose);
  // The frames/s and the mean error once the timed loop took `seconds`.
  void finish(double seconds);
};

// A method timed beside the engine in one report.
struct BenchPeer {
  std::string row;        // its row in the table
  std::string short_name;  // in the ratios line
  std::string json_name;  // <json_name>_hz, <json_name>_found
  BenchRun run;
};

// The engine (and the peers) on one kind of frames at one resolution.
struct BenchKindRun {
  BenchKind kind = BenchKind::Virtual;
  BenchRun full, tracked;
  std::vector<BenchPeer> peers;
};

struct BenchResolution {
  cv::Size size;
  std::vector<BenchKindRun> kinds;  // virtual, then real scenes when there are photographs
};

// --frames (at least 10, default 200), --format (text or json), --resolution (WxH or all:
// 640x480, 1280x720, 1920x1080), --backgrounds (the real scenes' photographs), --config
// (the pipeline); UsageError naming the option otherwise, InputError for a bad config.
struct BenchOptions {
  int frames = 200;
  std::string format = "text";
  std::vector<cv::Size> sizes;
  std::string backgrounds;
  // The pipeline timed: --config FILE's (its methods and parameters; the bench scene keeps
  // its own camera and scene), the defaults without one.
  PipelineOptions pipeline;
};
// The options benchOptions reads.
inline const std::vector<std::string> kBenchOptionNames{"frames", "resolution", "format", "backgrounds"};
BenchOptions benchOptions(const Args& args);

BenchSequence renderBenchFrames(cv::Size size, int frames);

// The engine over the sequence once to grow its buffers, then timed.
BenchRun timeEngine(const BenchSequence& sequence, TrackingMode tracking);

// `detect(grey, pose)` over `frames`, timed and its allocations counted (the caller warms it up).
template <class Detect>
BenchRun timeDetector(const std::vector<Frame>& frames, Detect&& detect) {
  using Clock = std::chrono::steady_clock;
  BenchRun run;
  run.frames = static_cast<int>(frames.size());
  Pose pose;
  const auto start = Clock::now();
  startCountingAllocations();
  for (const Frame& f : frames)
    if (ok(detect(f.image, pose))) run.notePose(f.truth, pose);
  run.allocations = stopCountingAllocations();
  run.finish(std::chrono::duration<double>(Clock::now() - start).count());
  return run;
}

// Times `sequence`'s peers (those of its kind) into `r.peers`, after the engine.
using PeerTiming = std::function<void(const BenchSequence& sequence, BenchKindRun& r)>;

// At every resolution of `options`, on one core, for each kind of frames: renders them,
// times the engine with tracking off and on, then the peers, and prints the report (text
// as each is done, JSON at the end).
void runBench(const BenchOptions& options, const PeerTiming& time_peers = {});

}  // namespace imagepro::cli
