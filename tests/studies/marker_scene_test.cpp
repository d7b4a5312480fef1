// The reference marker drawn by the real-scene generator (studies/marker_scene.h): over a
// photograph at the frame's pose, read back by OpenCV at that pose, the photograph intact
// away from its card.
#include "studies/marker_scene.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "core/reconstruction/test_scenes.h"

namespace imagepro::studies {
namespace {

TEST(MarkerScene, PaintedOverAPhotographAtThePose) {
  const CameraModel cam;
  const TargetGeometry target;
  cv::Mat photo(cam.height, cam.width, CV_8UC1);
  for (int v = 0; v < photo.rows; ++v)
    for (int u = 0; u < photo.cols; ++u)
      photo.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(100 + 60 * std::sin(0.03 * u) * std::cos(0.02 * v));
  const MarkerGeometry marker = markerLikeTarget(target, 130.0);
  EXPECT_EQ(marker.square_mm, 2.0 * target.radius_mm);
  TargetLook look;
  look.white = 210;
  look.black = 25;
  look.card_size_mm = 130.0;
  const ScenePainter paint = markerPainter(cam, marker);
  for (const Pose& truth : {poseAlongRay(cam, {250, 200}, 700, 30, 40, 20), poseAlongRay(cam, {420, 300}, 1000, 50, 200, -120)}) {
    cv::Mat scene, frame;
    paint(photo, truth, look, scene);
    ASSERT_EQ(scene.type(), CV_32FC1);
    scene.convertTo(frame, CV_8U);
    Pose found;
    ASSERT_EQ(estimateMarkerPose(cam, marker, frame, found), Status::Ok);
    EXPECT_LT(testing::rotationErrorDeg(truth, found), 1.0);
    EXPECT_LT(testing::positionErrorPercent(truth, found), 0.5);
    // The look's ink on the card, and the photograph exact beyond the card's image.
    double lo = 255, hi = 0;
    cv::minMaxLoc(frame, &lo, &hi);
    EXPECT_LE(lo, look.black + 1);
    std::vector<cv::Point2f> corners;
    for (const auto& [x, y] : {std::pair{-65.0, -65.0}, {65.0, -65.0}, {65.0, 65.0}, {-65.0, 65.0}}) {
      const Eigen::Vector2d p = projectIdeal(cam, rotationMatrix(truth) * Eigen::Vector3d(x, y, 0) + translation(truth));
      corners.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    }
    const cv::Rect box = cv::boundingRect(corners) + cv::Size(2, 2) - cv::Point(1, 1);
    const cv::Rect changed = cv::boundingRect(frame != photo);
    EXPECT_GT(changed.area(), box.area() / 2);
    EXPECT_EQ(changed & box, changed);
  }
}

}  // namespace
}  // namespace imagepro::studies
