// Virtual perspective projection speed (thesis 2.2, 6.1: "100 ideal frames ... per second").
//   build/tests/bench/bench_render --benchmark_min_time=0.5
// Frames/s is reported as items_per_second. Poses: "far" is the default scene (target
// 800 mm ahead, 100 px disk on a 130 px card), "near" fills most of the 640x480 image.
#include <benchmark/benchmark.h>

#include "core/source/virtual_renderer.h"

namespace {

using namespace imagepro;

CameraModel camera(bool distorted) {
  CameraModel cam;
  if (distorted) cam.distortion = kThesisCameraDistortion;
  return cam;
}

const Pose kFar{20, -15, 10, 30, -20, 800};
const Pose kNear{20, -15, 10, 0, 0, 260};

void run(benchmark::State& state, const VirtualSceneOptions& scene, const Pose& pose, bool pattern = false) {
  const CameraModel cam = camera(state.range(0) != 0);
  const TargetGeometry target;
  const PatternGeometry grid;
  cv::Mat out;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    if (pattern)
      renderPattern(cam, target, grid, scene, pose, out, seed++);
    else
      renderTarget(cam, target, scene, pose, out, seed++);
    benchmark::DoNotOptimize(out.data);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(state.range(0) ? "distorted" : "no distortion");
}

VirtualSceneOptions binary() {
  VirtualSceneOptions s;
  s.mode = RenderMode::Binary;
  return s;
}

void BM_RenderBinaryFar(benchmark::State& state) { run(state, binary(), kFar); }
void BM_RenderBinaryNear(benchmark::State& state) { run(state, binary(), kNear); }
void BM_RenderBinaryClutter(benchmark::State& state) {
  VirtualSceneOptions s = binary();
  s.clutter = 12;
  run(state, s, kFar);
}
void BM_RenderGreyFar(benchmark::State& state) { run(state, VirtualSceneOptions{}, kFar); }
void BM_RenderGreyNear(benchmark::State& state) { run(state, VirtualSceneOptions{}, kNear); }
void BM_RenderGreyAllEffects(benchmark::State& state) {
  VirtualSceneOptions s;
  s.clutter = 12;
  s.blur_sigma_px = 1.0;
  s.noise_sigma = 4.0;
  s.illumination_gradient = 0.3;
  run(state, s, kFar);
}
// The anti-aliasing's cost: samples per edge pixel, supersampling^2 (the near pose, distorted).
void BM_RenderGreySupersampling(benchmark::State& state) {
  VirtualSceneOptions s;
  s.supersampling = static_cast<int>(state.range(1));
  run(state, s, kNear);
}
void BM_RenderPatternGrey(benchmark::State& state) { run(state, VirtualSceneOptions{}, Pose{30, 20, 5, 0, 0, 900}, true); }

BENCHMARK(BM_RenderBinaryFar)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderBinaryNear)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderBinaryClutter)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderGreyFar)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderGreyNear)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderGreyAllEffects)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderGreySupersampling)
    ->Args({1, 4})
    ->Args({1, 8})
    ->Args({1, 16})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RenderPatternGrey)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
