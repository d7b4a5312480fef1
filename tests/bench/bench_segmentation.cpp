// Segmentation (thesis 2.3, table 2.1): histogram, AT-Orig vs AT-Mod, binarization, and
// OpenCV's Otsu threshold on the same frames, one core. Frames: the Virtual source's
// grey target at several poses with clutter, noise, blur and uneven, dim lighting.
//   build/tests/bench/bench_segmentation --benchmark_min_time=0.2 --benchmark_repetitions=10
//       --benchmark_report_aggregates_only=true
// On a shared machine the "_min" rows (best repetition) are the least disturbed figures.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <algorithm>
#include <chrono>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>  // _mm_clflush, for the cold-region benchmark
#endif

#include "core/pipeline/engine.h"
#include "core/reconstruction/features.h"
#include "core/segmentation/histogram.h"
#include "core/segmentation/reduce.h"
#include "core/segmentation/threshold.h"
#include "core/source/bench_scene.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

struct TestFrames {
  std::vector<cv::Mat> grey;
  std::vector<Histogram> hist;
};

const TestFrames& frames() {
  static const TestFrames f = [] {
    cv::setNumThreads(1);  // one core for OpenCV too
    const CameraModel camera;  // 640 x 480
    const TargetGeometry target;
    const Pose poses[] = {{0, 0, 0, 0, 0, 800},        {20, -15, 30, 120, -60, 900},
                          {-35, 10, -80, -150, 80, 1200}, {10, 40, 150, 60, 100, 650},
                          {0, -50, 10, -200, -120, 1500}, {45, 0, 0, 0, 0, 1000},
                          {-15, -25, -170, 180, 30, 700},  {5, 5, 60, -40, -150, 1800}};
    TestFrames out;
    for (int i = 0; i < 8; ++i) {
      VirtualSceneOptions scene;
      scene.mode = RenderMode::Grey;
      scene.clutter = 4 + i;
      scene.seed = 100 + i;
      scene.noise_sigma = 2.0 + i % 3 * 2.0;
      scene.blur_sigma_px = 0.5 + 0.2 * (i % 4);
      scene.illumination_gradient = 0.1 * (i % 5);
      scene.white_level = 150 + 12 * i;  // dim to bright lighting
      scene.black_level = 12 + 2 * i;
      scene.background_level = 60 + 10 * i;
      cv::Mat grey;
      renderTarget(camera, target, scene, poses[i], grey, i);
      Histogram h;
      computeHistogram(grey, h);
      out.grey.push_back(grey);
      out.hist.push_back(h);
    }
    return out;
  }();
  return f;
}

constexpr int kFrames = 8;

double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

void Histogram640x480(benchmark::State& state) {
  const auto& f = frames();
  Histogram h;
  int i = 0;
  for (auto _ : state) {
    computeHistogram(f.grey[i++ % kFrames], h);
    benchmark::DoNotOptimize(h.data());
  }
}
BENCHMARK(Histogram640x480)->ComputeStatistics("min", minimum);

// The histogram passes of a tracked frame, as views into the frame: the search region
// (143 x 145, about the bench scene's) and the target crop that is re-thresholded (91 x 89).
void regionArgs(benchmark::internal::Benchmark* b) {
  b->Args({143, 145})->Args({91, 89})->ArgNames({"w", "h"})->ComputeStatistics("min", minimum);
}

cv::Mat regionView(const cv::Mat& grey, const benchmark::State& state) {
  const int w = static_cast<int>(state.range(0)), h = static_cast<int>(state.range(1));
  return grey(cv::Rect(320 - w / 2 + 1, 240 - h / 2, w, h));  // an odd column: rows not aligned
}

// Warm: the region is in the cache, as in a loop over a few frames.
void HistogramRegion(benchmark::State& state) {
  const auto& f = frames();
  Histogram h;
  int i = 0;
  for (auto _ : state) {
    computeHistogram(regionView(f.grey[i++ % kFrames], state), h);
    benchmark::DoNotOptimize(h.data());
  }
}
BENCHMARK(HistogramRegion)->Apply(regionArgs);

#if defined(__SSE2__)
// Cold: the region's cache lines are flushed before each pass, as a camera frame
// arrives (written by DMA); only the pass is timed.
void HistogramRegionCold(benchmark::State& state) {
  const auto& f = frames();
  Histogram h;
  int i = 0;
  for (auto _ : state) {
    const cv::Mat view = regionView(f.grey[i++ % kFrames], state);
    for (int r = 0; r < view.rows; ++r)
      for (int c = 0; c < view.cols + 63; c += 64) _mm_clflush(view.ptr(r) + std::min(c, view.cols - 1));
    _mm_mfence();
    const auto start = std::chrono::steady_clock::now();
    computeHistogram(view, h);
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(h.data());
  }
}
BENCHMARK(HistogramRegionCold)->Apply(regionArgs)->UseManualTime();
#endif

// Table 2.1: threshold and time per image, from the histogram.
template <Status (*kThreshold)(const Histogram&, int&)>
void ThresholdFromHistogram(benchmark::State& state) {
  const Histogram& h = frames().hist[state.range(0)];
  int t = -1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(kThreshold(h, t));
    benchmark::DoNotOptimize(t);
  }
  state.counters["threshold"] = t;
}
BENCHMARK(ThresholdFromHistogram<thresholdAtOrig>)
    ->Name("AtOrig")
    ->DenseRange(0, kFrames - 1)
    ->ComputeStatistics("min", minimum);
BENCHMARK(ThresholdFromHistogram<thresholdAtMod>)
    ->Name("AtMod")
    ->DenseRange(0, kFrames - 1)
    ->ComputeStatistics("min", minimum);

// The two histograms AT-Mod sees per tracked frame of the realistic bench scene
// (core/source/bench_scene.h): the tracked search region, and the crop about the
// detected target that is re-thresholded for its contour (thesis 5.2.2).
struct TrackedHistograms {
  std::vector<Histogram> region, crop;
};

const TrackedHistograms& trackedHistograms() {
  static const TrackedHistograms f = [] {
    cv::setNumThreads(1);
    const Settings s = benchSceneSettings({640, 480});
    Engine engine(s);
    FrameResult r;
    TrackedHistograms out;
    for (const Frame& frame : renderBenchSequence(s, 50)) {
      engine.process(frame, r);
      if (r.search_region == cv::Rect({}, frame.image.size()) || r.targets.empty()) continue;
      out.region.push_back(r.histogram);
      cv::Rect crop;
      if (!ok(targetCrop(r.targets.front().ellipse, s.pipeline.reconstruction.crop_margin_px, frame.image.size(), crop)))
        continue;
      Histogram h;
      computeHistogram(frame.image(crop), h);
      out.crop.push_back(h);
    }
    return out;
  }();
  return f;
}

// AT-Mod on those histograms in turn: argument 0 the search regions, 1 the target crops.
void AtModTracked(benchmark::State& state) {
  const auto& f = trackedHistograms();
  const std::vector<Histogram>& hists = state.range(0) == 0 ? f.region : f.crop;
  std::size_t i = 0;
  int t = -1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(thresholdAtMod(hists[i], t));
    benchmark::DoNotOptimize(t);
    if (++i == hists.size()) i = 0;
  }
  double pixels = 0;
  for (const Histogram& h : hists)
    for (const auto n : h) pixels += n;
  state.counters["histograms"] = static_cast<double>(hists.size());
  state.counters["pixels"] = pixels / static_cast<double>(hists.size());
}
BENCHMARK(AtModTracked)->ArgName("crop")->DenseRange(0, 1)->ComputeStatistics("min", minimum);

// The goal: histogram + AT-Mod per 640 x 480 frame.
void HistogramAtMod(benchmark::State& state) {
  const auto& f = frames();
  Histogram h;
  int t = -1, i = 0;
  for (auto _ : state) {
    computeHistogram(f.grey[i++ % kFrames], h);
    benchmark::DoNotOptimize(thresholdAtMod(h, t));
  }
}
BENCHMARK(HistogramAtMod)->ComputeStatistics("min", minimum);

void Binarize640x480(benchmark::State& state) {
  const auto& f = frames();
  cv::Mat binary;
  int i = 0;
  for (auto _ : state) {
    binarize(f.grey[i++ % kFrames], 100, binary);
    benchmark::DoNotOptimize(binary.data);
  }
}
BENCHMARK(Binarize640x480)->ComputeStatistics("min", minimum);

// The coarse search's reduced image (reduce.h) beside OpenCV's area resize to the same
// size: factor 2 (640 x 480 frames), 3 and 6 (1920 x 1080 frames: here on a 640 x 480 one).
void Reduce640x480(benchmark::State& state) {
  const auto& f = frames();
  const int k = static_cast<int>(state.range(0));
  cv::Mat reduced;
  std::vector<std::uint16_t> ws;
  int i = 0;
  for (auto _ : state) {
    reduceByBlockMean(f.grey[i++ % kFrames], k, reduced, ws);
    benchmark::DoNotOptimize(reduced.data);
  }
}
BENCHMARK(Reduce640x480)->ArgName("factor")->Arg(2)->Arg(3)->Arg(6)->ComputeStatistics("min", minimum);

void OpenCvResizeArea640x480(benchmark::State& state) {
  const auto& f = frames();
  const int k = static_cast<int>(state.range(0));
  cv::Mat reduced;
  int i = 0;
  for (auto _ : state) {
    cv::resize(f.grey[i++ % kFrames], reduced, cv::Size(640 / k, 480 / k), 0, 0, cv::INTER_AREA);
    benchmark::DoNotOptimize(reduced.data);
  }
}
BENCHMARK(OpenCvResizeArea640x480)->ArgName("factor")->Arg(2)->Arg(3)->Arg(6)->ComputeStatistics("min", minimum);

// Side by side with OpenCV's Otsu, which also histograms and binarizes.
void HistogramAtModBinarize(benchmark::State& state) {
  const auto& f = frames();
  Histogram h;
  cv::Mat binary;
  int t = -1, i = 0;
  for (auto _ : state) {
    const cv::Mat& grey = f.grey[i++ % kFrames];
    computeHistogram(grey, h);
    benchmark::DoNotOptimize(thresholdAtMod(h, t));
    binarize(grey, t, binary);
    benchmark::DoNotOptimize(binary.data);
  }
}
BENCHMARK(HistogramAtModBinarize)->ComputeStatistics("min", minimum);

void OpenCvOtsuBinarize(benchmark::State& state) {
  const auto& f = frames();
  cv::Mat binary;
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        cv::threshold(f.grey[i++ % kFrames], binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
    benchmark::DoNotOptimize(binary.data);
  }
}
BENCHMARK(OpenCvOtsuBinarize)->ComputeStatistics("min", minimum);

// Otsu's threshold per image, beside table 2.1's rows.
void OpenCvOtsu(benchmark::State& state) {
  const cv::Mat& grey = frames().grey[state.range(0)];
  cv::Mat binary;
  double t = -1;
  for (auto _ : state) {
    t = cv::threshold(grey, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    benchmark::DoNotOptimize(binary.data);
  }
  state.counters["threshold"] = t;
}
BENCHMARK(OpenCvOtsu)->DenseRange(0, kFrames - 1)->ComputeStatistics("min", minimum);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
