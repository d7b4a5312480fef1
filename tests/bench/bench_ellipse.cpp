// Ellipse detection (thesis 2.6, table 2.6): the whole stage per frame with the direct
// fit and with Bennett's per-path accumulator, and, on the same paths, the fit alone
// next to OpenCV's cv::fitEllipseDirect, one core. Frames: ten cluttered 640x480
// Virtual-source grey frames (samples 0-9, like the rows of table 2.6): the target at
// ten poses among 6 to 42 white clutter bars and rectangles, noise, blur and uneven
// lighting (the disk the brightest object), binarized by AT-Mod, Laplace edges and CN1
// paths (outside the timing).
//   taskset -c 1 build/tests/bench/bench_ellipse --benchmark_min_time=0.2
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true   (one line)
// The stage's counters: stage_fitted (paths the stage fitted, last frame),
// stage_fitted_pixels, consensus_fits (0 on every table frame) and target_found.
// Each method runs per frame (/frame:0 ... /frame:9) and over all ten in turn
// (frame:-1; its per_frame is the mean time per frame).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "core/connectivity/connectivity.h"
#include "core/edges/edges.h"
#include "core/ellipse/detect.h"
#include "bench_frames.h"

namespace imagepro {
namespace {

constexpr int kFrames = bench::kTableFrames;
const cv::Size kImage(640, 480);

const std::vector<Paths>& frames() {
  static const std::vector<Paths> f = [] {
    cv::setNumThreads(1);  // one core for OpenCV too
    std::vector<Paths> out;
    for (int i = 0; i < kFrames; ++i) {
      const cv::Mat binary = bench::binaryTableFrame({.clutter_first = 6, .clutter_step = 4, .seed_first = 300,
                                                      .gradient_period = 4, .white_first = 180, .white_step = 6},
                                                     i);
      EdgeList edges;
      detectEdgesLaplace(binary, edges);
      Paths paths;
      ConnectivityWorkspace ws;
      connectCN1(edges, binary.size(), paths, ws);
      out.push_back(std::move(paths));
    }
    return out;
  }();
  return f;
}

std::size_t fittedPaths(const Paths& p) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < p.pathCount(); ++i) n += p.path(i).size() >= std::size_t(EllipseOptions{}.min_path_pixels);
  return n;
}

// The table frames in turn (bench_frames.h), with this stage's counters for one frame.
template <class Step>
void runFrames(benchmark::State& state, Step step) {
  const int only = bench::runTableFrames(state, step);
  if (only != bench::kAllTableFrames) {
    const Paths& p = frames()[static_cast<std::size_t>(only)];
    state.counters["edge_pixels"] = static_cast<double>(p.pixels.size());
    state.counters["paths"] = static_cast<double>(p.pathCount());
    state.counters["fitted"] = static_cast<double>(fittedPaths(p));
  }
}

void detectStage(benchmark::State& state, EllipseMethod method) {
  const auto& f = frames();
  EllipseOptions o;
  o.method = method;
  const TargetGeometry g;
  EllipseWorkspace ws;
  std::vector<TargetDetection> out;
  int found = 0, runs = 0;
  std::size_t fitted = 0, fitted_pixels = 0;  // paths the stage fitted and their pixels (last frame)
  runFrames(state, [&](int i) {
    const Paths& p = f[static_cast<std::size_t>(i)];
    found += ok(detectTarget(o, g, p, kImage, ws, out)) && out[0].spots_found;
    ++runs;
    benchmark::DoNotOptimize(out.data());
    fitted = fitted_pixels = 0;
    for (std::size_t k = 0; k < ws.paths.size(); ++k)
      if (ws.paths[k].fitted) ++fitted, fitted_pixels += p.path(k).size();
  });
  state.counters["target_found"] = runs ? double(found) / runs : 0.0;
  state.counters["stage_fitted"] = static_cast<double>(fitted);
  state.counters["stage_fitted_pixels"] = static_cast<double>(fitted_pixels);
  state.counters["consensus_fits"] = static_cast<double>(ws.consensus_fits);
}

void DirectFitStage(benchmark::State& state) { detectStage(state, EllipseMethod::DirectFit); }
void BennettStage(benchmark::State& state) { detectStage(state, EllipseMethod::Bennett); }

// Shape-only classification of every path (as the thesis's table 2.6 timed it: every
// connected path tested, no spot pre-selection).
void everyPath(benchmark::State& state, EllipseMethod method) {
  const auto& f = frames();
  EllipseOptions o;
  o.method = method;
  EllipseWorkspace ws;
  std::vector<TargetDetection> out;
  runFrames(state, [&](int i) {
    detectEllipses(o, f[static_cast<std::size_t>(i)], kImage, ws, out);
    benchmark::DoNotOptimize(out.data());
  });
}

void DirectFitEveryPath(benchmark::State& state) { everyPath(state, EllipseMethod::DirectFit); }
void BennettEveryPath(benchmark::State& state) { everyPath(state, EllipseMethod::Bennett); }

// The fit alone (moments, Halir-Flusser solve, ellipse parameters) on every path of at
// least min_path_pixels: the work cv::fitEllipseDirect does.
void FitOnly(benchmark::State& state) {
  const auto& f = frames();
  const std::size_t min_pixels = std::size_t(EllipseOptions{}.min_path_pixels);
  EllipseFit fit;
  runFrames(state, [&](int i) {
    const Paths& p = f[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < p.pathCount(); ++k) {
      if (p.path(k).size() < min_pixels) continue;
      ConicMoments m;
      m.add(p.path(k));
      benchmark::DoNotOptimize(fitEllipse(m, fit));
    }
  });
}

void OpenCvFitEllipseDirect(benchmark::State& state) {
  const auto& f = frames();
  const std::size_t min_pixels = std::size_t(EllipseOptions{}.min_path_pixels);
  std::vector<cv::Point> points;
  runFrames(state, [&](int i) {
    const Paths& p = f[static_cast<std::size_t>(i)];
    for (std::size_t k = 0; k < p.pathCount(); ++k) {
      const auto path = p.path(k);
      if (path.size() < min_pixels) continue;
      points.clear();
      for (const EdgePixel& e : path) points.emplace_back(e.x, e.y);
      benchmark::DoNotOptimize(cv::fitEllipseDirect(points));
    }
  });
}

BENCHMARK(DirectFitStage)->Apply(bench::tableFrameArgs);
BENCHMARK(BennettStage)->Apply(bench::tableFrameArgs);
BENCHMARK(DirectFitEveryPath)->Apply(bench::tableFrameArgs);
BENCHMARK(BennettEveryPath)->Apply(bench::tableFrameArgs);
BENCHMARK(FitOnly)->Apply(bench::tableFrameArgs);
BENCHMARK(OpenCvFitEllipseDirect)->Apply(bench::tableFrameArgs);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
