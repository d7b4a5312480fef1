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
#include "bench_frames.h"

namespace imagepro {
namespace {

constexpr int kFrames = bench::kTableFrames;

struct TestFrames {
  std::vector<cv::Mat> binary;
  std::vector<EdgeList> laplace;  // connectivity input, as in table 2.3
};

const TestFrames& frames() {
  static const TestFrames f = [] {
    cv::setNumThreads(1);  // one core for OpenCV too
    TestFrames out;
    for (int i = 0; i < kFrames; ++i) {
      const cv::Mat binary = bench::binaryTableFrame({.clutter_first = 0, .clutter_step = 4, .seed_first = 200,
                                                      .gradient_period = 5, .white_first = 160, .white_step = 9},
                                                     i);
      EdgeList edges;
      detectEdgesLaplace(binary, edges);
      out.binary.push_back(binary);
      out.laplace.push_back(std::move(edges));
    }
    return out;
  }();
  return f;
}

// The table frames in turn (bench_frames.h), with this stage's counters for one frame.
template <class Step>
void runFrames(benchmark::State& state, Step step) {
  const int only = bench::runTableFrames(state, step);
  if (only != bench::kAllTableFrames) {
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

BENCHMARK(SobelThinning)->Apply(bench::tableFrameArgs);
BENCHMARK(Laplace)->Apply(bench::tableFrameArgs);
BENCHMARK(CN0)->Apply(bench::tableFrameArgs);
BENCHMARK(CN1)->Apply(bench::tableFrameArgs);
BENCHMARK(LaplaceThenCN1)->Apply(bench::tableFrameArgs);
BENCHMARK(OpenCvFindContours)->Apply(bench::tableFrameArgs);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
