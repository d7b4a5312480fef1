// Edges and connectivity (thesis 2.4-2.5, tables 2.2 and 2.3): Sobel + thinning vs
// Laplace, CN0 vs CN1, and OpenCV's cv::findContours (RETR_LIST, CHAIN_APPROX_NONE)
// on the same binary frames, one core. Frames: ten 640x480 Virtual-source grey frames
// of the target at several poses with 0 to 36 clutter bars and rectangles, noise,
// blur and uneven lighting, binarized by AT-Mod (eq. 2.1), as the pipeline does.
//   build/tests/bench/bench_edges --benchmark_min_time=0.5
// Each method runs per frame (/0 ... /9, like the rows of the thesis tables) and over
// all ten in turn (frame:-1; its per_frame is the mean time per frame).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "core/connectivity/connectivity.h"
#include "core/edges/edges.h"
#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

constexpr int kFrames = 10;
constexpr int kAllFrames = -1;

struct TestFrames {
  std::vector<cv::Mat> binary;
  std::vector<EdgeList> laplace;  // connectivity input, as in table 2.3
};

const TestFrames& frames() {
  static const TestFrames f = [] {
    cv::setNumThreads(1);  // one core for OpenCV too
    const CameraModel camera;  // 640 x 480
    const TargetGeometry target;
    const Pose poses[kFrames] = {{0, 0, 0, 0, 0, 800},          {20, -15, 30, 120, -60, 900},
                                 {-35, 10, -80, -150, 80, 1200}, {10, 40, 150, 60, 100, 650},
                                 {0, -50, 10, -200, -120, 1500}, {45, 0, 0, 0, 0, 1000},
                                 {-15, -25, -170, 180, 30, 700}, {5, 5, 60, -40, -150, 1800},
                                 {30, 30, 90, 250, 170, 900},    {-5, 20, -30, 20, 10, 450}};
    TestFrames out;
    for (int i = 0; i < kFrames; ++i) {
      VirtualSceneOptions scene;
      scene.mode = RenderMode::Grey;
      scene.clutter = 4 * i;
      scene.seed = 200 + static_cast<unsigned>(i);
      scene.noise_sigma = 2.0 + i % 3 * 2.0;
      scene.blur_sigma_px = 0.5 + 0.2 * (i % 4);
      scene.illumination_gradient = 0.1 * (i % 5);
      scene.white_level = 160 + 9 * i;
      scene.black_level = 12 + 2 * i;
      scene.background_level = 60 + 8 * i;
      cv::Mat grey, binary;
      renderTarget(camera, target, scene, poses[i], grey, static_cast<std::uint64_t>(i));
      Histogram h;
      computeHistogram(grey, h);
      int t = 128;
      if (!ok(computeThreshold(ThresholdOptions{ThresholdMethod::AtMod, 128}, h, t))) t = 128;
      binarize(grey, t, binary);
      EdgeList edges;
      detectEdgesLaplace(binary, edges);
      out.binary.push_back(binary);
      out.laplace.push_back(std::move(edges));
    }
    return out;
  }();
  return f;
}

// Runs `step(frame)` on one frame (range(0) >= 0) or on all frames in turn.
template <class Step>
void runFrames(benchmark::State& state, Step step) {
  const int only = static_cast<int>(state.range(0));
  int i = 0;
  for (auto _ : state) {
    step(only == kAllFrames ? i : only);
    i = (i + 1) % kFrames;
  }
  state.counters["per_frame"] =
      benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  if (only != kAllFrames) {
    state.counters["edge_pixels"] = static_cast<double>(frames().laplace[static_cast<std::size_t>(only)].size());
  }
}

void SobelThinning(benchmark::State& state) {
  const auto& f = frames();
  EdgeList out;
  EdgeWorkspace ws;
  runFrames(state, [&](int i) {
    detectEdgesSobelThinning(f.binary[static_cast<std::size_t>(i)], out, ws);
    benchmark::DoNotOptimize(out.data());
  });
}

void Laplace(benchmark::State& state) {
  const auto& f = frames();
  EdgeList out;
  runFrames(state, [&](int i) {
    detectEdgesLaplace(f.binary[static_cast<std::size_t>(i)], out);
    benchmark::DoNotOptimize(out.data());
  });
}

void CN0(benchmark::State& state) {
  const auto& f = frames();
  Paths paths;
  ConnectivityWorkspace ws;
  runFrames(state, [&](int i) {
    connectCN0(f.laplace[static_cast<std::size_t>(i)], f.binary[0].size(), paths, ws);
    benchmark::DoNotOptimize(paths.pixels.data());
  });
}

void CN1(benchmark::State& state) {
  const auto& f = frames();
  Paths paths;
  ConnectivityWorkspace ws;
  runFrames(state, [&](int i) {
    connectCN1(f.laplace[static_cast<std::size_t>(i)], f.binary[0].size(), paths, ws);
    benchmark::DoNotOptimize(paths.pixels.data());
  });
}

// Edge detection and connectivity together, the work cv::findContours does in one call.
void LaplaceThenCN1(benchmark::State& state) {
  const auto& f = frames();
  EdgeList edges;
  Paths paths;
  ConnectivityWorkspace ws;
  runFrames(state, [&](int i) {
    const cv::Mat& binary = f.binary[static_cast<std::size_t>(i)];
    detectEdgesLaplace(binary, edges);
    connectCN1(edges, binary.size(), paths, ws);
    benchmark::DoNotOptimize(paths.pixels.data());
  });
}

void OpenCvFindContours(benchmark::State& state) {
  const auto& f = frames();
  std::vector<std::vector<cv::Point>> contours;
  runFrames(state, [&](int i) {
    cv::findContours(f.binary[static_cast<std::size_t>(i)], contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
    benchmark::DoNotOptimize(contours.data());
  });
}

void frameArgs(benchmark::internal::Benchmark* b) {
  for (int i = 0; i < kFrames; ++i) b->Arg(i);
  b->Arg(kAllFrames);
  b->ArgName("frame");
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(SobelThinning)->Apply(frameArgs);
BENCHMARK(Laplace)->Apply(frameArgs);
BENCHMARK(CN0)->Apply(frameArgs);
BENCHMARK(CN1)->Apply(frameArgs);
BENCHMARK(LaplaceThenCN1)->Apply(frameArgs);
BENCHMARK(OpenCvFindContours)->Apply(frameArgs);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
