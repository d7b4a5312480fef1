// Reconstruction stage speed (goal: crop to pose <= 50 us per frame on one core):
// crop + re-threshold + contour + spots + distortion correction + fit + pose, per contour
// mode and target distance, on grey 640x480 frames with noise, blur and the thesis camera's
// distortion; and its parts.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "core/ellipse/direct_fit.h"
#include "core/reconstruction/pose.h"
#include "core/reconstruction/reconstruct.h"
#include "core/reconstruction/refine.h"
#include "core/reconstruction/undistort.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct Scene {
  Settings settings;
  Pose pose;
  cv::Mat image;
  Ellipse detected;

  Scene(double distanceMm, ContourMode mode) {
    settings.camera().distortion = kThesisCameraDistortion;
    settings.virtual_scene.noise_sigma = 2.0;
    settings.virtual_scene.blur_sigma_px = 0.6;
    settings.virtual_scene.clutter = 6;
    settings.pipeline.reconstruction.contour_mode = mode;
    // 35 deg of tilt, a little off the image centre.
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(35 * kDeg, Eigen::Vector3d(0.6, 0.8, 0)) *
                               Eigen::AngleAxisd(20 * kDeg, Eigen::Vector3d::UnitZ()))
                                  .toRotationMatrix();
    pose = poseFromRt(R, Eigen::Vector3d(30, -20, distanceMm));
    renderTarget(settings.camera(), settings.target, settings.virtual_scene, pose, image, 1);
    // The rim as the detection stage reports it (the seen rim's best ellipse).
    std::vector<Eigen::Vector2d> rim;
    const Eigen::Vector3d T = translation(pose);
    for (int i = 0; i < 180; ++i) {
      const double a = 2 * M_PI * i / 180;
      rim.push_back(distortPixel(settings.camera(),
                                 projectIdeal(settings.camera(), R * Eigen::Vector3d(50 * std::cos(a), 50 * std::sin(a), 0) + T)));
    }
    EllipseFit fit;
    fitEllipseDirect(std::span<const Eigen::Vector2d>(rim), fit);
    detected = fit.ellipse;
  }
};

// Crop to pose on `scene` with `config`, every iteration; the rim's points and the crop's
// size as counters.
void timeCropToPose(benchmark::State& state, const Scene& scene, const ReconstructionConfig& config) {
  ReconstructionWorkspace ws;
  ReconstructionResult result;
  for (auto _ : state) {
    const Status s = reconstructTarget(config, scene.image, scene.detected, 128, ws, result);
    if (!ok(s)) state.SkipWithError("reconstruction failed");
    benchmark::DoNotOptimize(result.pose);
  }
  state.counters["points"] = static_cast<double>(result.contour.size());
  state.counters["crop_px"] = static_cast<double>(result.crop.area());
}

void BM_CropToPose(benchmark::State& state) {
  const Scene scene(static_cast<double>(state.range(0)), static_cast<ContourMode>(state.range(1)));
  ReconstructionConfig config = reconstructionConfig(scene.settings);
  if (state.range(2) == 0) config.rethreshold.method = ThresholdMethod::None;  // the frame's threshold
  timeCropToPose(state, scene, config);
}
// (distance mm, contour mode, re-threshold AT-Mod 1 / None 0): every mode at 800 mm; the
// default mode near and far, and without its own re-threshold.
BENCHMARK(BM_CropToPose)
    ->ArgNames({"mm", "mode", "rethreshold"})
    ->Args({800, static_cast<int>(ContourMode::EightPointsOrg), 1})
    ->Args({800, static_cast<int>(ContourMode::EightPointsMod), 1})
    ->Args({800, static_cast<int>(ContourMode::FullPathOrg), 1})
    ->Args({800, static_cast<int>(ContourMode::FullPathMod), 1})
    ->Args({800, static_cast<int>(ContourMode::SubPixel), 1})
    ->Args({400, static_cast<int>(ContourMode::SubPixel), 1})
    ->Args({1200, static_cast<int>(ContourMode::SubPixel), 1})
    ->Args({800, static_cast<int>(ContourMode::SubPixel), 0})
    ->Args({400, static_cast<int>(ContourMode::SubPixel), 0})
    ->Unit(benchmark::kMicrosecond);

void BM_PoseFromEllipse(benchmark::State& state) {
  const Scene scene(800, ContourMode::SubPixel);
  ReconstructionWorkspace ws;
  ReconstructionResult result;
  reconstructTarget(reconstructionConfig(scene.settings), scene.image, scene.detected, 128, ws, result);
  Pose pose;
  for (auto _ : state) {
    poseFromEllipse(scene.settings.camera(), scene.settings.target, result.conic, result.centre_spot_ideal,
                    result.offset_spot_ideal, pose, state.range(0) != 0);
    benchmark::DoNotOptimize(pose);
  }
}
// centre_spot:0 takes the normal from the rim alone, 1 weighs the centre spot in (the default).
BENCHMARK(BM_PoseFromEllipse)->ArgNames({"centre_spot"})->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// The whole reconstruction with refine_pose (refine.h) on, default mode, at the three
// The rim edge model (rim_edge_model, rim_edge.h) off and on, the default sub-pixel mode at
// three distances: the difference is the model's cost.
void BM_CropToPoseRimEdgeModel(benchmark::State& state) {
  const Scene scene(static_cast<double>(state.range(0)), ContourMode::SubPixel);
  ReconstructionConfig config = reconstructionConfig(scene.settings);
  config.options.rim_edge_model = state.range(1) != 0;
  timeCropToPose(state, scene, config);
}
BENCHMARK(BM_CropToPoseRimEdgeModel)
    ->ArgNames({"mm", "model"})
    ->ArgsProduct({{400, 800, 1200}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

// distances: the difference to BM_CropToPose/mm:D/mode:4/rethreshold:1 is the refinement's cost.
void BM_CropToPoseRefined(benchmark::State& state) {
  const Scene scene(static_cast<double>(state.range(0)), ContourMode::SubPixel);
  ReconstructionConfig config = reconstructionConfig(scene.settings);
  config.options.refine_pose = true;
  ReconstructionWorkspace ws;
  ReconstructionResult result;
  for (auto _ : state) {
    const Status s = reconstructTarget(config, scene.image, scene.detected, 128, ws, result);
    if (!ok(s) || !ok(result.steps.refine)) state.SkipWithError("reconstruction or refinement failed");
    benchmark::DoNotOptimize(result.pose);
  }
  state.counters["points"] = static_cast<double>(result.contour.size());
}
BENCHMARK(BM_CropToPoseRefined)->ArgNames({"mm"})->Arg(400)->Arg(800)->Arg(1200)->Unit(benchmark::kMicrosecond);

// The refinement alone, from the analytic pose of the frame (what refine_pose adds).
void BM_RefinePose(benchmark::State& state) {
  const Scene scene(static_cast<double>(state.range(0)), ContourMode::SubPixel);
  ReconstructionWorkspace ws;
  ReconstructionResult result;
  reconstructTarget(reconstructionConfig(scene.settings), scene.image, scene.detected, 128, ws, result);
  PoseRefinement refined;
  for (auto _ : state) {
    const Status s = refinePose(scene.settings.camera(), scene.settings.target, result.contour_ideal,
                                result.centre_spot_ideal, result.offset_spot_ideal, result.pose, refined);
    if (!ok(s)) state.SkipWithError("refinement failed");
    benchmark::DoNotOptimize(refined.pose);
  }
  state.counters["points"] = static_cast<double>(result.contour_ideal.size());
  state.counters["steps"] = refined.iterations;
}
BENCHMARK(BM_RefinePose)->ArgNames({"mm"})->Arg(400)->Arg(800)->Arg(1200)->Unit(benchmark::kMicrosecond);

void BM_UndistortPoint(benchmark::State& state) {
  CameraModel cam;
  cam.distortion = kThesisCameraDistortion;
  const bool exact = state.range(0) != 0;
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 256; ++i) points.emplace_back(20 + 2.3 * i, 30 + 1.6 * i);
  std::vector<Eigen::Vector2d> work = points;
  for (auto _ : state) {
    work = points;
    undistortPoints(cam, exact, work);
    benchmark::DoNotOptimize(work.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(points.size()));
}
BENCHMARK(BM_UndistortPoint)->ArgNames({"exact"})->Arg(0)->Arg(1);

}  // namespace
}  // namespace imagepro

BENCHMARK_MAIN();
