// The whole engine per frame on the realistic bench scene (core/source/bench_scene.h),
// full frame and tracked side by side, so a change to any stage shows in the figure
// that matters. `imagepro-cli bench` adds the peers and the allocation count.
//   build/tests/bench/bench_engine --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>

#include "core/pipeline/engine.h"
#include "core/source/bench_scene.h"

namespace imagepro {
namespace {

constexpr int kFrames = 100;

const std::vector<Frame>& frames() {
  static const std::vector<Frame> sequence = renderBenchSequence(benchSceneSettings({640, 480}), kFrames);
  return sequence;
}

void runEngine(benchmark::State& state, TrackingMode mode, ContourMode contour, bool coarse = true) {
  cv::setNumThreads(1);
  Settings s = benchSceneSettings({640, 480});
  s.pipeline.tracking.mode = mode;
  s.pipeline.binarization.coarse_search = coarse;
  s.pipeline.reconstruction.contour_mode = contour;
  Engine engine(s);
  FrameResult r;
  for (const Frame& f : frames()) engine.process(f, r);  // buffers grow to size once
  std::size_t i = 0;
  int found = 0;
  for (auto _ : state) {
    engine.process(frames()[i], r);
    found += ok(r.status) ? 1 : 0;
    if (++i == frames().size()) i = 0;
  }
  state.counters["found%"] = 100.0 * found / static_cast<double>(state.iterations());
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void FullFrame(benchmark::State& state) { runEngine(state, TrackingMode::Off, ContourMode::SubPixel); }
// The baseline of the coarse search (stage_chain.h): every pass at full size.
void FullFrameWithoutCoarseSearch(benchmark::State& state) {
  runEngine(state, TrackingMode::Off, ContourMode::SubPixel, false);
}
void Tracked(benchmark::State& state) { runEngine(state, TrackingMode::Corners2D, ContourMode::SubPixel); }
void TrackedFullPathMod(benchmark::State& state) {
  runEngine(state, TrackingMode::Corners2D, ContourMode::FullPathMod);
}

BENCHMARK(FullFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(FullFrameWithoutCoarseSearch)->Unit(benchmark::kMicrosecond);
BENCHMARK(Tracked)->Unit(benchmark::kMicrosecond);
BENCHMARK(TrackedFullPathMod)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
