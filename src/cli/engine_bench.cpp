#include "cli/engine_bench.h"

#include <sys/resource.h>

#include <opencv2/core/utility.hpp>

#include <cstdio>

#include "core/pipeline/engine.h"
#include "core/source/bench_scene.h"

namespace imagepro::cli {

namespace {

using Clock = std::chrono::steady_clock;

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5));
  return v[k];
}

long peakMemoryKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

std::string jsonResolution(const BenchResolution& r) {
  char buf[256];
  std::string out;
  std::snprintf(buf, sizeof buf, "{\"width\": %d, \"height\": %d, \"frames\": %d, \"full_frame_hz\": %.1f, \"tracked_hz\": %.1f",
                r.size.width, r.size.height, r.full.frames, r.full.hz, r.tracked.hz);
  out += buf;
  for (const BenchPeer& p : r.peers) {
    std::snprintf(buf, sizeof buf, ", \"%s_hz\": %.1f", p.json_name.c_str(), p.run.hz);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, ", \"full_frame_found\": %d, \"tracked_found\": %d", r.full.found, r.tracked.found);
  out += buf;
  for (const BenchPeer& p : r.peers) {
    std::snprintf(buf, sizeof buf, ", \"%s_found\": %d", p.json_name.c_str(), p.run.found);
    out += buf;
  }
  std::snprintf(buf, sizeof buf,
                ", \"full_frame_allocations_per_frame\": %.3f, \"tracked_allocations_per_frame\": %.3f, "
                "\"tracked_region_fraction\": %.4f}",
                r.full.allocationsPerFrame(), r.tracked.allocationsPerFrame(), r.tracked.mean_region_fraction);
  return out + buf;
}

}  // namespace

void BenchRun::notePose(const std::optional<Pose>& truth, const Pose& pose) {
  ++found;
  if (truth) mean_position_error_mm += (translation(*truth) - translation(pose)).norm();
}

void BenchRun::finish(double seconds) {
  hz = frames / std::max(seconds, 1e-12);
  if (found > 0) mean_position_error_mm /= found;
}

BenchOptions benchOptions(const Args& args) {
  BenchOptions options;
  options.frames = args.integer("frames", 200);
  if (options.frames < 10) throw UsageError("--frames must be at least 10");
  options.format = args.valueOr("format", "text");
  if (options.format != "text" && options.format != "json") throw UsageError("--format must be text or json");
  const std::string resolution = args.valueOr("resolution", "640x480");
  if (resolution == "all") {
    options.sizes = {{640, 480}, {1280, 720}, {1920, 1080}};
  } else {
    int w = 0, h = 0;
    if (std::sscanf(resolution.c_str(), "%dx%d", &w, &h) != 2 || w < 160 || h < 120 || w > 8192 || h > 8192)
      throw UsageError("--resolution must be WxH (e.g. 1280x720) or all");
    options.sizes = {{w, h}};
  }
  return options;
}

BenchSequence renderBenchFrames(cv::Size size, int frames) {
  BenchSequence sequence;
  sequence.settings = benchSceneSettings(size);
  sequence.frames = renderBenchSequence(sequence.settings, frames);
  return sequence;
}

BenchRun timeEngine(const BenchSequence& sequence, TrackingMode tracking) {
  Settings s = sequence.settings;
  s.pipeline.tracking.mode = tracking;
  Engine engine(s);
  FrameResult r;
  // A first pass grows every buffer to its working size.
  for (const Frame& f : sequence.frames) engine.process(f, r);
  engine.resetTracking();
  BenchRun run;
  run.frames = static_cast<int>(sequence.frames.size());
  run.times.reserve(sequence.frames.size());
  double area = 0.0;
  const auto start = Clock::now();
  startCountingAllocations();
  for (const Frame& f : sequence.frames) {
    engine.process(f, r);
    if (ok(r.status) && r.pose) run.notePose(f.truth, *r.pose);
    run.times.push_back(r.times);
    area += static_cast<double>(r.search_region.area()) / (f.image.cols * f.image.rows);
  }
  run.allocations = stopCountingAllocations();
  run.finish(std::chrono::duration<double>(Clock::now() - start).count());
  // The reservations above happen before counting; push_back within capacity is free.
  run.mean_region_fraction = area / std::max(1, run.frames);
  return run;
}

namespace {

// The engine's rows, the peers' rows, their ratios, the tracked region and the
// per-stage median and 99th percentile.
void printBenchText(const BenchResolution& r) {
  std::printf("\n== %dx%d, %d frames (grey, blur 0.8 px, noise 3, 8 clutter objects, moving target)\n",
              r.size.width, r.size.height, r.full.frames);
  std::printf("%-26s %12s %10s %14s %16s\n", "pipeline", "frames/s", "found", "mean |dT| mm", "allocs/frame");
  auto row = [](const std::string& name, const BenchRun& run) {
    std::printf("%-26s %12.0f %6d/%-4d %14.2f %16.2f\n", name.c_str(), run.hz, run.found, run.frames,
                run.mean_position_error_mm, run.allocationsPerFrame());
  };
  row("ImagePro full frame", r.full);
  row("ImagePro tracked", r.tracked);
  for (const BenchPeer& p : r.peers) row(p.row, p.run);
  if (!r.peers.empty()) {
    std::string ratios;
    char buf[96];
    for (const auto& [name, engine] : {std::pair{"full", &r.full}, std::pair{"tracked", &r.tracked}})
      for (const BenchPeer& p : r.peers) {
        std::snprintf(buf, sizeof buf, "%s%s/%s %.1fx", ratios.empty() ? "" : ", ", name, p.short_name.c_str(),
                      engine->hz / p.run.hz);
        ratios += buf;
      }
    std::printf("ratios: %s\n", ratios.c_str());
  }
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

// After every resolution: the JSON object of them all, or the peak memory line of the text.
void printBenchEnd(const std::vector<BenchResolution>& results, const std::string& format) {
  if (format != "json") {
    std::printf("\npeak memory %.1f MB (including the pre-rendered frames)\n", peakMemoryKb() / 1024.0);
    return;
  }
  // The first resolution's rates at the top, for a quick look.
  const BenchResolution& first = results.front();
  std::printf("{\"full_frame_hz\": %.1f, \"tracked_hz\": %.1f", first.full.hz, first.tracked.hz);
  for (const BenchPeer& p : first.peers) std::printf(", \"%s_hz\": %.1f", p.json_name.c_str(), p.run.hz);
  std::printf(", \"peak_memory_kb\": %ld, \"resolutions\": [", peakMemoryKb());
  for (std::size_t i = 0; i < results.size(); ++i) std::printf("%s%s", i ? ", " : "", jsonResolution(results[i]).c_str());
  std::printf("]}\n");
}

}  // namespace

void runBench(const BenchOptions& options, const PeerTiming& time_peers) {
  // One core for everybody: OpenCV would otherwise spread a peer's work over threads.
  cv::setNumThreads(1);
  std::vector<BenchResolution> results;
  for (const cv::Size& size : options.sizes) {
    std::fprintf(stderr, "rendering %d frames at %dx%d ...\n", options.frames, size.width, size.height);
    const BenchSequence sequence = renderBenchFrames(size, options.frames);
    BenchResolution r;
    r.size = size;
    std::fprintf(stderr, "timing ImagePro (full frame, tracked) ...\n");
    r.full = timeEngine(sequence, TrackingMode::Off);
    r.tracked = timeEngine(sequence, TrackingMode::Corners2D);
    if (time_peers) time_peers(sequence, r);
    if (options.format == "text") printBenchText(r);
    results.push_back(std::move(r));
  }
  printBenchEnd(results, options.format);
}

}  // namespace imagepro::cli
