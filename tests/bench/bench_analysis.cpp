// Case-study analysis speed (thesis 5.3): both targets of a two-target frame
// reconstructed (whole frame, no tracking), and the pendulum analysis of a 10 s record
// at 25 frames/s (period, constrained sphere fit, g).
#include <benchmark/benchmark.h>

#include "core/analysis/pendulum.h"
#include "core/analysis/two_targets.h"
#include "core/source/virtual_motion.h"

namespace imagepro {
namespace {

void BM_ReconstructTwoTargets(benchmark::State& state) {
  Settings s;
  s.camera().distortion = kThesisCameraDistortion;
  s.virtual_scene.noise_sigma = 2.0;
  cv::Mat image;
  TwoTargetRenderWorkspace render_ws;
  renderTwoTargets(s.camera(), s.target, s.virtual_scene, {}, twoTargetStudyPosition(static_cast<int>(state.range(0))),
                   image, 1, render_ws);
  MultiTargetWorkspace ws;
  MultiTargetResult result;
  TwoTargetMeasurement m;
  for (auto _ : state) {
    reconstructAllTargets(s, image, ws, result);
    if (!ok(measureTwoTargets(result, m))) state.SkipWithError("not two targets");
    benchmark::DoNotOptimize(m);
  }
}
BENCHMARK(BM_ReconstructTwoTargets)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

void BM_AnalyzePendulum(benchmark::State& state) {
  VirtualSceneOptions scene;
  scene.motion.kind = MotionKind::Pendulum;
  std::vector<PoseSample> samples;
  for (int i = 0; i < state.range(0); ++i) {
    PoseSample p;
    p.t_s = i / 25.0;
    p.valid = true;
    p.pose = virtualPoseAt(scene, p.t_s);
    samples.push_back(p);
  }
  PendulumAnalysis a;
  for (auto _ : state) {
    if (!ok(analyzePendulum(samples, {}, a))) state.SkipWithError("analysis failed");
    benchmark::DoNotOptimize(a.g_m_s2);
  }
}
BENCHMARK(BM_AnalyzePendulum)->Arg(250)->Arg(2500)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
