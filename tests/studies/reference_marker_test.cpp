#include "studies/reference_marker.h"

#include <gtest/gtest.h>

#include "core/source/virtual_renderer.h"
#include "core/reconstruction/status_print.h"
#include "core/reconstruction/test_scenes.h"

namespace imagepro::studies {
namespace {

using testing::makePose;

struct MarkerTest : ::testing::Test {
  CameraModel cam;
  TargetGeometry target;
  VirtualSceneOptions scene;
  MarkerGeometry marker;
  cv::Mat frame;

  void render(const Pose& pose) {
    VirtualSceneOptions plain = scene;
    plain.blur_sigma_px = plain.noise_sigma = plain.illumination_gradient = 0;
    renderTarget(cam, target, plain, pose, frame);
    paintMarkerCard(cam, marker, scene, pose, frame);
    applySceneEffects(scene, 1, frame);
  }
};

TEST_F(MarkerTest, IdentityPoseReadsAsIdentity) {
  // With neither blur nor noise, OpenCV's corners of this exactly head-on square were
  // resolved by IPPE 9 deg off at 8 x 8 and 16 x 16 samples per edge pixel (not at 2-6 or
  // 12); no camera gives such a frame, so this one has a lens's 0.6 px of blur.
  scene.blur_sigma_px = 0.6;
  Pose truth;
  truth.tz_mm = 700;
  render(truth);
  Pose est;
  ASSERT_EQ(estimateMarkerPose(cam, marker, frame, est), Status::Ok);
  EXPECT_LT(testing::rotationErrorDeg(truth, est), 1.0);
  EXPECT_NEAR(est.tz_mm, 700, 3.5);
  EXPECT_NEAR(est.rz_deg, 0, 0.5);
}

TEST_F(MarkerTest, RecoversPosesWithDistortionBlurAndNoise) {
  cam.distortion = kThesisCameraDistortion;
  scene.blur_sigma_px = 0.7;
  scene.noise_sigma = 2;
  for (const Pose& truth : {makePose(cam, 500, 35, 20, 120, 300, 250), makePose(cam, 900, 50, -60, -170, 380, 200),
                            makePose(cam, 700, 20, 100, 179.5, 250, 280)}) {
    render(truth);
    Pose est;
    ASSERT_EQ(estimateMarkerPose(cam, marker, frame, est), Status::Ok) << truth.tz_mm;
    EXPECT_LT(testing::rotationErrorDeg(truth, est), 1.0) << truth.tz_mm;
    EXPECT_LT(testing::positionErrorPercent(truth, est), 0.5) << truth.tz_mm;
  }
}

TEST_F(MarkerTest, NotFoundAndFoundTwice) {
  frame = cv::Mat(480, 640, CV_8UC1, cv::Scalar(110));
  Pose est;
  EXPECT_EQ(estimateMarkerPose(cam, marker, frame, est), Status::NoTarget);
  EXPECT_EQ(estimateMarkerPose(cam, marker, cv::Mat(), est), Status::EmptyFrame);
  paintMarkerCard(cam, marker, scene, makePose(cam, 1000, 10, 0, 0, 180, 240), frame);
  paintMarkerCard(cam, marker, scene, makePose(cam, 1000, 10, 0, 30, 460, 240), frame);
  EXPECT_EQ(estimateMarkerPose(cam, marker, frame, est), Status::AmbiguousTarget);
}

}  // namespace
}  // namespace imagepro::studies
