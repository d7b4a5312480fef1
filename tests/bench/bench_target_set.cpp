// The engine per frame with a set of targets (settings "targets"): two and four targets
// moving in a 640 x 480 frame, each in its own quarter, full frame and tracked side by
// side, beside one target of the same print alone in the same frames' scene.
//   build/tests/bench/bench_target_set --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <map>
#include <vector>

#include "core/pipeline/engine.h"
#include "core/source/target_set_scene.h"

namespace imagepro {
namespace {

constexpr int kFrames = 100;

// Members 1..n coded at 0.2, 0.4, 0.6, 0.8 of the radius (4 mm spots); with one, the
// settings' lone target instead.
Settings setOf(int n) {
  Settings s;
  s.pipeline.binarization.coarse_search = true;
  if (n == 1) return s;
  for (int i = 0; i < n; ++i) {
    TargetSpec t;
    t.id = i + 1;
    t.geometry.spot_radius_mm = 3.0;
    t.geometry.spot_offset_mm = (n == 2 ? 20.0 + 10.0 * i : 10.0 + 10.0 * i);
    s.targets.push_back(t);
  }
  return s;
}

// The frames' scene: uniform noise blurred into soft blotches of grey 90-170.
cv::Mat sceneBackground(const CameraModel& camera) {
  cv::Mat background(camera.height, camera.width, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(background, cv::RNG::UNIFORM, 90, 170);
  cv::GaussianBlur(background, background, cv::Size(0, 0), 6.0);
  return background;
}

// Each target circles in its own quarter of the frame at 1.1-1.3 m, turning and tilting.
const std::vector<Frame>& frames(int n) {
  static std::map<int, std::vector<Frame>> sequences;
  auto& sequence = sequences[n];
  if (!sequence.empty()) return sequence;
  const Settings s = setOf(n);
  const CameraModel& camera = s.camera();
  const cv::Mat background = sceneBackground(camera);
  std::vector<TargetGeometry> geometry;
  for (int i = 0; i < std::max(n, 1); ++i) geometry.push_back(n == 1 ? s.target : s.targets[i].geometry);
  for (int k = 0; k < kFrames; ++k) {
    std::vector<Pose> poses;
    for (int i = 0; i < std::max(n, 1); ++i) {
      const double phase = 2.0 * M_PI * k / kFrames + i;
      const double cx = (i % 2 ? 170.0 : -170.0) + 30.0 * std::cos(phase);
      const double cy = (i / 2 ? 120.0 : -120.0) * (n > 2 ? 1.0 : 0.0) + 25.0 * std::sin(phase);
      poses.push_back(Pose{20.0 * std::sin(phase), 15.0 * std::cos(phase), 3.6 * k, cx, cy, 1200.0 + 100.0 * i / 2});
    }
    Frame f;
    composeTargets(background, camera, geometry, TargetLook{}, poses, f.image);
    f.index = k;
    f.timestamp_s = k / 30.0;
    sequence.push_back(f);
  }
  return sequence;
}

void runSet(benchmark::State& state, int n, bool tracked) {
  cv::setNumThreads(1);
  Settings s = setOf(n);
  s.pipeline.tracking.mode = tracked ? TrackingMode::Corners2D : TrackingMode::Off;
  Engine engine(s);
  FrameResult r;
  for (const Frame& f : frames(n)) engine.process(f, r);  // buffers grow to size once
  std::size_t i = 0;
  double told = 0.0;
  for (auto _ : state) {
    engine.process(frames(n)[i], r);
    if (n == 1) {
      told += ok(r.status) ? 1.0 : 0.0;
    } else {
      for (const TargetSummary& t : r.targets) told += t.target_id >= 0 && ok(t.status) ? 1.0 : 0.0;
    }
    if (++i == frames(n).size()) i = 0;
  }
  state.counters["found%"] = 100.0 * told / (std::max(n, 1) * static_cast<double>(state.iterations()));
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The frames' scene with no target at all: noise over the same blurred background.
const std::vector<Frame>& emptyFrames() {
  static std::vector<Frame> sequence;
  if (!sequence.empty()) return sequence;
  const Settings defaults;
  const cv::Mat background = sceneBackground(defaults.camera());
  cv::RNG rng(11);
  for (int k = 0; k < 10; ++k) {
    Frame f;
    cv::Mat noise(background.size(), CV_16SC1);
    rng.fill(noise, cv::RNG::NORMAL, 0, 3);
    background.convertTo(f.image, CV_16SC1);
    f.image += noise;
    f.image.convertTo(f.image, CV_8UC1);
    f.index = k;
    f.timestamp_s = k / 30.0;
    sequence.push_back(f);
  }
  return sequence;
}

void runEmpty(benchmark::State& state, int n) {
  cv::setNumThreads(1);
  Engine engine(setOf(n));
  FrameResult r;
  for (const Frame& f : emptyFrames()) engine.process(f, r);
  std::size_t i = 0;
  double told = 0.0;
  for (auto _ : state) {
    engine.process(emptyFrames()[i], r);
    told += ok(r.status) ? 1.0 : 0.0;
    if (++i == emptyFrames().size()) i = 0;
  }
  state.counters["found%"] = 100.0 * told / static_cast<double>(state.iterations());
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void NoTargetOneTarget(benchmark::State& state) { runEmpty(state, 1); }
void NoTargetTwoTargets(benchmark::State& state) { runEmpty(state, 2); }
void NoTargetFourTargets(benchmark::State& state) { runEmpty(state, 4); }

void OneTargetFullFrame(benchmark::State& state) { runSet(state, 1, false); }
void OneTargetTracked(benchmark::State& state) { runSet(state, 1, true); }
void TwoTargetsFullFrame(benchmark::State& state) { runSet(state, 2, false); }
void TwoTargetsTracked(benchmark::State& state) { runSet(state, 2, true); }
void FourTargetsFullFrame(benchmark::State& state) { runSet(state, 4, false); }
void FourTargetsTracked(benchmark::State& state) { runSet(state, 4, true); }

BENCHMARK(OneTargetFullFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(OneTargetTracked)->Unit(benchmark::kMicrosecond);
BENCHMARK(TwoTargetsFullFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(TwoTargetsTracked)->Unit(benchmark::kMicrosecond);
BENCHMARK(FourTargetsFullFrame)->Unit(benchmark::kMicrosecond);
BENCHMARK(FourTargetsTracked)->Unit(benchmark::kMicrosecond);
BENCHMARK(NoTargetOneTarget)->Unit(benchmark::kMicrosecond);
BENCHMARK(NoTargetTwoTargets)->Unit(benchmark::kMicrosecond);
BENCHMARK(NoTargetFourTargets)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
