#include "cli/engine_bench.h"

#include <sys/resource.h>

#include <opencv2/core/utility.hpp>

#include <cstdio>

#include "core/pipeline/engine.h"
#include "cli/real_bench_scene.h"
#include "core/source/background_photos.h"
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

const char* prefix(BenchKind kind) { return kind == BenchKind::Real ? "real_" : ""; }

// Allocations per frame to two decimals, or `uncounted` in a build that counts none (a
// sanitizer build): a 0 there would claim what was not measured.
std::string allocationsPerFrame(const BenchRun& run, const char* uncounted) {
  if (!allocationCountingAvailable()) return uncounted;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", run.allocationsPerFrame());
  return buf;
}

// A kind's keys, prefixed "real_" for the real scenes: rates, poses found, allocations.
std::string jsonKind(const BenchKindRun& k) {
  const char* p = prefix(k.kind);
  char buf[256];
  std::string out;
  std::snprintf(buf, sizeof buf, ", \"%sframes\": %d, \"%sfull_frame_hz\": %.1f, \"%stracked_hz\": %.1f", p,
                k.full.frames, p, k.full.hz, p, k.tracked.hz);
  out += buf;
  for (const BenchPeer& peer : k.peers) {
    std::snprintf(buf, sizeof buf, ", \"%s%s_hz\": %.1f", p, peer.json_name.c_str(), peer.run.hz);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, ", \"%sfull_frame_found\": %d, \"%stracked_found\": %d", p, k.full.found, p,
                k.tracked.found);
  out += buf;
  for (const BenchPeer& peer : k.peers) {
    std::snprintf(buf, sizeof buf, ", \"%s%s_found\": %d", p, peer.json_name.c_str(), peer.run.found);
    out += buf;
  }
  std::snprintf(buf, sizeof buf,
                ", \"%sfull_frame_allocations_per_frame\": %s, \"%stracked_allocations_per_frame\": %s, "
                "\"%stracked_region_fraction\": %.4f",
                p, allocationsPerFrame(k.full, "null").c_str(), p, allocationsPerFrame(k.tracked, "null").c_str(), p,
                k.tracked.mean_region_fraction);
  return out + buf;
}

std::string jsonResolution(const BenchResolution& r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "{\"width\": %d, \"height\": %d", r.size.width, r.size.height);
  std::string out = buf;
  for (const BenchKindRun& k : r.kinds) out += jsonKind(k);
  return out + "}";
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
  options.backgrounds = args.valueOr("backgrounds", defaultBackgroundsDir());
  options.pipeline = loadConfig(args).pipeline;
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
void printBenchText(const BenchKindRun& r, cv::Size size) {
  if (r.kind == BenchKind::Virtual)
    std::printf("\n== %dx%d, virtual scene, %d frames (grey, blur 0.8 px, noise 3, 8 clutter objects, moving target)\n",
                size.width, size.height, r.full.frames);
  else
    std::printf("\n== %dx%d, real scenes, %d frames (the target moving over photographs, %d frames each; light +-30 %%, "
                "blur 0.8 px, noise 2, JPEG 75)\n",
                size.width, size.height, r.full.frames, kRealBenchVideoFrames);
  std::printf("%-26s %12s %10s %14s %16s\n", "pipeline", "frames/s", "found", "mean |dT| mm", "allocs/frame");
  auto row = [](const std::string& name, const BenchRun& run) {
    std::printf("%-26s %12.0f %6d/%-4d %14.2f %16s\n", name.c_str(), run.hz, run.found, run.frames,
                run.mean_position_error_mm, allocationsPerFrame(run, "n/a").c_str());
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

// After every resolution: the JSON object of them all, or the text's summary of the
// rates and the peak memory.
void printBenchEnd(const std::vector<BenchResolution>& results, const std::string& format) {
  if (format != "json") {
    std::printf("\nsummary, frames/s            full frame      tracked\n");
    for (const BenchResolution& r : results)
      for (const BenchKindRun& k : r.kinds)
        std::printf("  %9s %-13s %12.0f %12.0f\n",
                    (std::to_string(r.size.width) + "x" + std::to_string(r.size.height)).c_str(),
                    k.kind == BenchKind::Real ? "real scenes" : "virtual", k.full.hz, k.tracked.hz);
    std::printf("\npeak memory %.1f MB (including the pre-rendered frames)\n", peakMemoryKb() / 1024.0);
    return;
  }
  // The first resolution's rates at the top, for a quick look.
  const BenchResolution& first = results.front();
  std::printf("{");
  const char* comma = "";
  for (const BenchKindRun& k : first.kinds) {
    const char* p = prefix(k.kind);
    std::printf("%s\"%sfull_frame_hz\": %.1f, \"%stracked_hz\": %.1f", comma, p, k.full.hz, p, k.tracked.hz);
    for (const BenchPeer& peer : k.peers) std::printf(", \"%s%s_hz\": %.1f", p, peer.json_name.c_str(), peer.run.hz);
    comma = ", ";
  }
  std::printf(", \"peak_memory_kb\": %ld, \"resolutions\": [", peakMemoryKb());
  for (std::size_t i = 0; i < results.size(); ++i) std::printf("%s%s", i ? ", " : "", jsonResolution(results[i]).c_str());
  std::printf("]}\n");
}

// The engine with tracking off and on, then the peers of the sequence's kind.
BenchKindRun timeKind(const BenchSequence& sequence, const PeerTiming& time_peers) {
  BenchKindRun r;
  r.kind = sequence.kind;
  std::fprintf(stderr, "timing ImagePro (full frame, tracked) ...\n");
  r.full = timeEngine(sequence, TrackingMode::Off);
  r.tracked = timeEngine(sequence, TrackingMode::Corners2D);
  if (time_peers) time_peers(sequence, r);
  return r;
}

}  // namespace

void runBench(const BenchOptions& options, const PeerTiming& time_peers) {
  // One core for everybody: OpenCV would otherwise spread a peer's work over threads.
  cv::setNumThreads(1);
  const bool text = options.format == "text";
  std::vector<BenchResolution> results;
  for (const cv::Size& size : options.sizes) {
    BenchResolution r;
    r.size = size;
    {  // each kind's frames are freed before the next kind's are rendered
      std::fprintf(stderr, "rendering %d frames at %dx%d ...\n", options.frames, size.width, size.height);
      BenchSequence rendered = renderBenchFrames(size, options.frames);
      rendered.settings.pipeline = options.pipeline;
      r.kinds.push_back(timeKind(rendered, time_peers));
      if (text) printBenchText(r.kinds.back(), size);
    }
    std::fprintf(stderr, "rendering %d real-scene frames at %dx%d ...\n", options.frames, size.width, size.height);
    BenchSequence real;
    std::string error;
    if (renderRealBenchFrames(size, options.frames, options.backgrounds, real, error)) {
      real.settings.pipeline = options.pipeline;
      r.kinds.push_back(timeKind(real, time_peers));
      if (text) printBenchText(r.kinds.back(), size);
    } else {
      // One line, and the virtual kind stands alone.
      std::fprintf(text ? stdout : stderr, "%sreal scenes: left out, %s (Debian's opencv-doc or --backgrounds DIR has some)\n",
                   text ? "\n" : "", error.c_str());
    }
    results.push_back(std::move(r));
  }
  printBenchEnd(results, options.format);
}

}  // namespace imagepro::cli
