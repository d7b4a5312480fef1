#include "core/reconstruction/spot_model.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "core/reconstruction/reconstruct.h"
#include "core/source/virtual_renderer.h"
#include "test_scenes.h"

namespace imagepro {
namespace {

// A disk seen head-on: rim radius 20 px, spots of 1 px radius at the centre and 10 px to
// the right of it, blurred so that neither gets as dark as the mid grey level.
struct SmallTarget {
  TargetGeometry target{50.0, 2.5, 25.0};
  Ellipse rim{60.0, 50.0, 20.0, 20.0, 0.0};
  cv::Mat grey{100, 120, CV_8UC1, cv::Scalar(20)};
  SmallTarget() {
    cv::circle(grey, {60, 50}, 20, cv::Scalar(200), cv::FILLED);
    cv::circle(grey, {60, 50}, 1, cv::Scalar(20), cv::FILLED);
    cv::circle(grey, {70, 50}, 1, cv::Scalar(20), cv::FILLED);
    cv::GaussianBlur(grey, grey, cv::Size(7, 7), 1.4);
  }
};

TEST(SpotModel, FindsFaintSpotsWhereTheGeometryPutsThem) {
  SmallTarget t;
  ASSERT_GT(t.grey.at<std::uint8_t>(50, 60), 110) << "the spot is fainter than the mid level";
  std::array<cv::Rect, 2> boxes;
  ASSERT_TRUE(spotBoxesByModel(t.grey, t.rim, t.target, 200, 20, boxes));
  EXPECT_TRUE(boxes[0].contains({60, 50})) << boxes[0];
  EXPECT_TRUE(boxes[1].contains({70, 50})) << boxes[1];
}

TEST(SpotModel, ADiskWithoutSpotsHasNone) {
  SmallTarget t;
  cv::Mat plain(100, 120, CV_8UC1, cv::Scalar(20));
  cv::circle(plain, {60, 50}, 20, cv::Scalar(200), cv::FILLED);
  std::array<cv::Rect, 2> boxes;
  EXPECT_FALSE(spotBoxesByModel(plain, t.rim, t.target, 200, 20, boxes));
  // Only the centre spot: no offset spot, no pair.
  cv::circle(plain, {60, 50}, 1, cv::Scalar(20), cv::FILLED);
  EXPECT_FALSE(spotBoxesByModel(plain, t.rim, t.target, 200, 20, boxes));
}

// A white ring round a dark hole (a photograph's ring or washer) has dark where both spots
// should be, but no paper round them: no spots, where the darkest points alone would pass.
TEST(SpotModel, TheHoleOfARingIsNoSpot) {
  SmallTarget t;
  cv::Mat ring(100, 120, CV_8UC1, cv::Scalar(20));
  cv::circle(ring, {60, 50}, 20, cv::Scalar(200), cv::FILLED);
  cv::ellipse(ring, {60, 50}, {13, 11}, 0.0, 0.0, 360.0, cv::Scalar(20), cv::FILLED);
  cv::GaussianBlur(ring, ring, cv::Size(5, 5), 0.8);
  ASSERT_LT(ring.at<std::uint8_t>(50, 60), 40);  // dark at the centre spot's place
  ASSERT_LT(ring.at<std::uint8_t>(50, 70), 40);  // and on the offset spot's circle
  std::array<cv::Rect, 2> boxes;
  EXPECT_FALSE(spotBoxesByModel(ring, t.rim, t.target, 200, 20, boxes));
  // Spots on the disk itself still pass.
  EXPECT_TRUE(spotBoxesByModel(t.grey, t.rim, t.target, 200, 20, boxes));
}

// A small target seen steeply (2.45 m, 62 deg: the rim 17 x 9 px), its spots 8 px apart
// along the long axis and too faint under 1.4 px of blur to be cut at the mid level. Two
// spots on the disk's narrow width: the circle round each for paper reaches past the disk
// into the card, and the grown box round the offset spot has no border pixel inside the
// rim's clearance and on its own side. Both spots are found where they are.
TEST(SpotModel, FindsTheSpotsOfASmallSteepTarget) {
  Settings settings;
  settings.virtual_scene.blur_sigma_px = 1.4;
  settings.virtual_scene.noise_sigma = 1.0;
  const CameraModel cam = settings.camera();
  const Pose pose = testing::makePose(cam, 2450, 62, 0, 0, 190.3, 294.6);
  cv::Mat image;
  renderTarget(cam, settings.target, settings.virtual_scene, pose, image, 5);
  ReconstructionWorkspace ws;
  ReconstructionResult result;
  const Ellipse rim = testing::seenRimEllipse(cam, settings.target, pose);
  const Status s = reconstructTarget(reconstructionConfig(settings), image, rim, 128, ws, result);
  ASSERT_EQ(result.steps.spots, Status::Ok) << statusName(s);
  EXPECT_EQ(result.spots.candidates, 0) << "too faint for the mid level: found by the model";
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  const Eigen::Vector2d centre = projectIdeal(cam, T);
  const Eigen::Vector2d offset = projectIdeal(cam, R * Eigen::Vector3d(settings.target.spot_offset_mm, 0, 0) + T);
  EXPECT_LT((result.spots.centre_spot - centre).norm(), 0.3);
  EXPECT_LT((result.spots.offset_spot - offset).norm(), 0.3);
}

TEST(SpotModel, BadInputIsNoSpots) {
  SmallTarget t;
  std::array<cv::Rect, 2> boxes;
  EXPECT_FALSE(spotBoxesByModel(cv::Mat(), t.rim, t.target, 200, 20, boxes));
  EXPECT_FALSE(spotBoxesByModel(t.grey, Ellipse{}, t.target, 200, 20, boxes));
  EXPECT_FALSE(spotBoxesByModel(t.grey, t.rim, t.target, 20, 200, boxes));  // no contrast
}

}  // namespace
}  // namespace imagepro
