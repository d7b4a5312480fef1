#pragma once
// The ten cluttered 640x480 frames the stage benchmarks run on (one per row, like the
// rows of thesis tables 2.2-2.6): the target at ten poses among clutter bars and
// rectangles, with noise, blur and uneven lighting, binarized by AT-Mod (eq. 2.1) as
// the pipeline does. Each benchmark keeps its own scene style so its figures stay
// comparable with the ones recorded in docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>

#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"
#include "core/source/virtual_renderer.h"

namespace imagepro::bench {

inline constexpr int kTableFrames = 10;
inline constexpr int kAllTableFrames = -1;  // the benchmark argument that cycles through them all

// Frames 0..9 one by one, then all ten in turn (frame:-1), in microseconds.
inline void tableFrameArgs(benchmark::internal::Benchmark* b) {
  for (int i = 0; i < kTableFrames; ++i) b->Arg(i);
  b->Arg(kAllTableFrames);
  b->ArgName("frame");
  b->Unit(benchmark::kMicrosecond);
}

// Runs `step(frame)` on the benchmark's frame, or on every frame in turn, and adds the
// mean time per frame as the counter per_frame. Returns the frame (kAllTableFrames: all).
template <class Step>
int runTableFrames(benchmark::State& state, Step step) {
  const int only = static_cast<int>(state.range(0));
  int i = 0;
  for (auto _ : state) {
    step(only == kAllTableFrames ? i : only);
    i = (i + 1) % kTableFrames;
  }
  state.counters["per_frame"] =
      benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  return only;
}

// How the scene of frame i varies with i.
struct ClutterStyle {
  int clutter_first = 0, clutter_step = 4;
  unsigned seed_first = 200;
  int gradient_period = 5;  // illumination gradient 0.1 * (i % period)
  int white_first = 160, white_step = 9;
};

// Frame i (0..kTableFrames-1), binarized at its AT-Mod threshold (128 when undefined).
inline cv::Mat binaryTableFrame(const ClutterStyle& style, int i) {
  static const Pose kPoses[kTableFrames] = {{0, 0, 0, 0, 0, 800},          {20, -15, 30, 120, -60, 900},
                                            {-35, 10, -80, -150, 80, 1200}, {10, 40, 150, 60, 100, 650},
                                            {0, -50, 10, -200, -120, 1500}, {45, 0, 0, 0, 0, 1000},
                                            {-15, -25, -170, 180, 30, 700}, {5, 5, 60, -40, -150, 1800},
                                            {30, 30, 90, 250, 170, 900},    {-5, 20, -30, 20, 10, 450}};
  VirtualSceneOptions scene;
  scene.mode = RenderMode::Grey;
  scene.clutter = style.clutter_first + style.clutter_step * i;
  scene.seed = style.seed_first + static_cast<unsigned>(i);
  scene.noise_sigma = 2.0 + i % 3 * 2.0;
  scene.blur_sigma_px = 0.5 + 0.2 * (i % 4);
  scene.illumination_gradient = 0.1 * (i % style.gradient_period);
  scene.white_level = style.white_first + style.white_step * i;
  scene.black_level = 12 + 2 * i;
  scene.background_level = 60 + 8 * i;
  cv::Mat grey, binary;
  renderTarget(CameraModel{}, TargetGeometry{}, scene, kPoses[i], grey, static_cast<std::uint64_t>(i));
  Histogram h;
  computeHistogram(grey, h);
  int t = 128;
  if (!ok(computeThreshold(ThresholdOptions{ThresholdMethod::AtMod, 128}, h, t))) t = 128;
  binarize(grey, t, binary);
  return binary;
}

}  // namespace imagepro::bench
