// Distance and angle between two targets (thesis 5.3.1): the object's geometry, the
// two-target renderer, the reconstruction of every target of a frame, against the
// known geometry; degenerate frames give named errors.
#include "core/analysis/two_targets.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/error_summary.h"
#include "core/source/virtual_renderer.h"
#include "support/plain_scene.h"

namespace imagepro {
namespace {

Settings studySettings(bool distorted, RenderMode mode = RenderMode::Grey) {
  Settings s = test::plainSettings();
  s.virtual_scene.mode = mode;
  s.virtual_scene.noise_sigma = mode == RenderMode::Grey ? 2.0 : 0.0;
  if (distorted) s.camera().distortion = kThesisCameraDistortion;
  return s;
}

TEST(TwoTargets, ObjectGeometryGivesTheKnownDistanceAndAngle) {
  for (const TwoTargetObject object : {TwoTargetObject{}, TwoTargetObject{150.0, 60.0}, TwoTargetObject{240.0, 120.0}})
    for (int position = 1; position <= 3; ++position) {
      const auto poses = twoTargetPoses(object, twoTargetStudyPosition(position));
      const TwoTargetMeasurement m = measureBetween(poses[0], poses[1]);
      EXPECT_NEAR(m.distance_mm, object.spacing_mm, 1e-9);
      EXPECT_NEAR(m.angle_deg, object.angle_deg, 1e-9);
      // Both face the camera and the left one is on the left.
      for (const Pose& p : poses) EXPECT_GT(rotationMatrix(p).col(2).dot(translation(p)), 0.0);
      EXPECT_LT(poses[0].tx_mm / poses[0].tz_mm, poses[1].tx_mm / poses[1].tz_mm);
    }
  // Square on, the targets are mirror images about the object's Y-Z plane.
  const auto poses = twoTargetPoses({}, Pose{0, 0, 0, 0, 0, 750});
  EXPECT_NEAR(poses[0].tx_mm, -100.0, 1e-9);
  EXPECT_NEAR(poses[1].tx_mm, 100.0, 1e-9);
  EXPECT_NEAR(poses[0].ry_deg, 45.0, 1e-9);
  EXPECT_NEAR(poses[1].ry_deg, -45.0, 1e-9);
}

TEST(TwoTargets, CardsMustFitOnTheirFaces) {
  EXPECT_TRUE(twoTargetObjectFits({}, 130.0));
  EXPECT_TRUE(twoTargetObjectFits({92.0, 90.0}, 130.0));   // 65.05 mm to the edge
  EXPECT_FALSE(twoTargetObjectFits({91.0, 90.0}, 130.0));  // 64.35 mm
  EXPECT_FALSE(twoTargetObjectFits({200.0, 0.0}, 130.0));
  EXPECT_FALSE(twoTargetObjectFits({200.0, 180.0}, 130.0));
  EXPECT_FALSE(twoTargetObjectFits({0.0, 90.0}, 130.0));
}

TEST(TwoTargets, RenderHoldsEachTargetAsItsOwnRenderShowsIt) {
  const Settings s = studySettings(false, RenderMode::Binary);
  const Pose object = twoTargetStudyPosition(2);
  const auto poses = twoTargetPoses({}, object);
  cv::Mat both, left, right;
  TwoTargetRenderWorkspace ws;
  renderTwoTargets(s.camera(), s.target, s.virtual_scene, {}, object, both, 0, ws);
  renderTarget(s.camera(), s.target, s.virtual_scene, poses[0], left);
  renderTarget(s.camera(), s.target, s.virtual_scene, poses[1], right);
  cv::Mat expected;
  cv::max(left, right, expected);  // white disks on black cards and background
  EXPECT_EQ(cv::norm(both, expected, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(left), 1000);
  EXPECT_GT(cv::countNonZero(right), 1000);
}

TEST(TwoTargets, GreyRenderLaysTheRightCardOverTheLeftRender) {
  Settings s = studySettings(false);
  s.virtual_scene.noise_sigma = 0.0;
  const Pose object = twoTargetStudyPosition(1);
  const auto poses = twoTargetPoses({}, object);
  cv::Mat both, left, right;
  TwoTargetRenderWorkspace ws;
  renderTwoTargets(s.camera(), s.target, s.virtual_scene, {}, object, both, 0, ws);
  renderTarget(s.camera(), s.target, s.virtual_scene, poses[0], left);
  renderTarget(s.camera(), s.target, s.virtual_scene, poses[1], right);
  const int background = s.virtual_scene.background_level;
  int checked = 0;
  for (int v = 0; v < both.rows; ++v)
    for (int u = 0; u < both.cols; ++u) {
      const int l = left.at<std::uint8_t>(v, u), r = right.at<std::uint8_t>(v, u), b = both.at<std::uint8_t>(v, u);
      if (l != background && r == background) {
        EXPECT_EQ(b, l) << u << "," << v;
        ++checked;
      } else if (r != background && l == background) {
        EXPECT_EQ(b, r) << u << "," << v;
        ++checked;
      }
    }
  EXPECT_GT(checked, 10000);
}

// Reconstructs both targets in `frames` noisy frames at a study position and returns
// the distance and angle errors.
void measurePosition(const Settings& s, int position, bool correct, int frames, std::vector<double>& distance,
                     std::vector<double>& angle) {
  Settings run = s;
  run.pipeline.reconstruction.distortion_correction = correct;
  const TwoTargetObject object;
  MultiTargetWorkspace ws;
  MultiTargetResult result;
  TwoTargetRenderWorkspace render_ws;
  cv::Mat image;
  for (int i = 0; i < frames; ++i) {
    VirtualSceneOptions scene = s.virtual_scene;
    applyStudyLighting(i < frames / 2 ? StudyLighting::Natural : StudyLighting::Extra, scene);
    renderTwoTargets(s.camera(), s.target, scene, object, twoTargetStudyPosition(position), image,
                     static_cast<std::uint64_t>(i), render_ws);
    ASSERT_EQ(reconstructAllTargets(run, image, ws, result), Status::Ok);
    ASSERT_EQ(result.targets.size(), 2u);
    TwoTargetMeasurement m;
    ASSERT_EQ(measureTwoTargets(result, m), Status::Ok) << "position " << position << " frame " << i;
    // Each reconstructed pose is the rendered one, left to right.
    const auto truth = twoTargetPoses(object, twoTargetStudyPosition(position));
    for (int k = 0; k < 2; ++k)
      EXPECT_LT((translation(result.targets[k].pose) - translation(truth[k])).norm(), 5.0);
    distance.push_back(m.distance_mm - object.spacing_mm);
    angle.push_back(m.angle_deg - object.angle_deg);
  }
}

TEST(TwoTargets, DistanceAndAngleWithinTheThesissErrorsWhenCorrected) {
  const Settings s = studySettings(true);
  for (int position = 1; position <= 3; ++position) {
    std::vector<double> distance, angle;
    measurePosition(s, position, true, 6, distance, angle);
    const ErrorSummary d = summarizeErrors(distance), a = summarizeErrors(angle);
    EXPECT_EQ(d.samples, 6);
    EXPECT_LT(d.max_abs, 0.5) << "position " << position;
    EXPECT_LT(a.max_abs, 0.5) << "position " << position;
  }
}

TEST(TwoTargets, UncorrectedDistortionShowsInTheAngle) {
  // The thesis camera's barrel distortion bends the images of the two tilted targets
  // apart: without correction the angle between their normals comes out larger.
  const Settings s = studySettings(true);
  for (int position : {1, 3}) {
    std::vector<double> with_d, with_a, without_d, without_a;
    measurePosition(s, position, true, 4, with_d, with_a);
    measurePosition(s, position, false, 4, without_d, without_a);
    EXPECT_GT(summarizeErrors(without_a).mean, std::abs(summarizeErrors(with_a).mean) + 0.2) << position;
  }
}

TEST(TwoTargets, FramesWithoutTwoTargetsGiveNamedErrors) {
  const Settings s = studySettings(false);
  MultiTargetWorkspace ws;
  MultiTargetResult result;
  TwoTargetMeasurement m;

  EXPECT_EQ(reconstructAllTargets(s, cv::Mat(), ws, result), Status::EmptyFrame);
  EXPECT_EQ(measureTwoTargets(result, m), Status::EmptyFrame);
  const cv::Mat flat(480, 640, CV_8UC1, cv::Scalar(90));
  EXPECT_EQ(reconstructAllTargets(s, flat, ws, result), Status::ThresholdUndefined);
  EXPECT_TRUE(result.targets.empty());

  // One target only.
  cv::Mat one;
  renderTarget(s.camera(), s.target, s.virtual_scene, Pose{0, 20, 0, -50, 0, 800}, one);
  ASSERT_EQ(reconstructAllTargets(s, one, ws, result), Status::Ok);
  EXPECT_EQ(result.reconstructed(), 1);
  EXPECT_EQ(measureTwoTargets(result, m), Status::TooFewTargets);

  // Three targets: which two?
  MultiTargetResult three = result;
  three.targets.assign(3, result.targets.front());
  EXPECT_EQ(measureTwoTargets(three, m), Status::AmbiguousTarget);
  // Two found, one of them not reconstructed: its reason.
  MultiTargetResult failed = result;
  failed.targets.assign(2, result.targets.front());
  failed.targets[1].status = Status::SpotsNotFound;
  EXPECT_EQ(measureTwoTargets(failed, m), Status::SpotsNotFound);
}

TEST(ErrorSummary, MeanStdAndLargestMagnitude) {
  const std::vector<double> e{1.0, -3.0, 2.0, 0.0};
  const ErrorSummary s = summarizeErrors(e);
  EXPECT_EQ(s.samples, 4);
  EXPECT_DOUBLE_EQ(s.mean, 0.0);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(14.0 / 4.0));
  EXPECT_DOUBLE_EQ(s.max_abs, 3.0);
  EXPECT_EQ(summarizeErrors({}).samples, 0);
}

}  // namespace
}  // namespace imagepro
