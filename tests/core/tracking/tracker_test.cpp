#include "core/tracking/tracker.h"

#include <gtest/gtest.h>

#include <cmath>

namespace imagepro {
namespace {

TrackingOptions noEnlargement() {
  TrackingOptions o;
  o.mode = TrackingMode::Corners2D;
  o.enlarge_px = 0;
  o.enlarge_scale = 0;
  o.enlarge_speed_scale = 0;
  o.reduction_percent = 100;  // no damping
  o.min_r = 0.0;
  return o;
}

const cv::Size kImage(640, 480);

TEST(Tracker, OffOrEmptyMeansWholeImage) {
  RegionTracker tracker;
  TrackingOptions o;
  EXPECT_FALSE(tracker.estimate(o, CameraModel{}, TargetGeometry{}, 0.0, kImage).has_value());
  tracker.observe(0.0, {100, 100, 50, 50}, std::nullopt);
  // One detection: the region about it, enlarged as usual (20 px + 10 %) and by a quarter
  // of its size on every side: 50 + 25 + 2 * 12.5 = 100 px, centred.
  const auto guess = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 0.04, kImage);
  ASSERT_TRUE(guess.has_value());
  EXPECT_EQ(*guess, cv::Rect(75, 75, 100, 100));
  o.mode = TrackingMode::Off;
  tracker.observe(0.04, {100, 100, 50, 50}, std::nullopt);
  EXPECT_FALSE(tracker.estimate(o, CameraModel{}, TargetGeometry{}, 0.08, kImage).has_value());
}

TEST(Tracker, ExtrapolatesALinearMotionExactly) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  o.degree = 1;
  o.data_points = 5;
  for (int i = 0; i < 6; ++i) tracker.observe(i * 0.04, {100.0 + 10 * i, 200.0 - 4 * i, 60, 40}, std::nullopt);
  const auto r = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 6 * 0.04, kImage);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->x, 160);
  EXPECT_EQ(r->y, 176);
  EXPECT_EQ(r->width, 60);
  EXPECT_EQ(r->height, 40);
}

TEST(Tracker, ExtrapolatesAQuadraticMotionWithDegreeTwo) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  o.degree = 2;
  o.data_points = 5;
  auto x = [](double t) { return 100 + 50 * t + 200 * t * t; };
  for (int i = 0; i < 8; ++i) tracker.observe(i * 0.1, {x(i * 0.1), 100, 50, 50}, std::nullopt);
  const auto r = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 0.8, kImage);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->x, static_cast<int>(std::floor(x(0.8) + 1e-9)));
  EXPECT_EQ(tracker.activeDegree(), 3);  // grown to the cap; the options limit the fit to 2
}

TEST(Tracker, CorrelationDropFallsBackToTwoPointsThenGrowsBack) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  o.degree = 1;
  o.data_points = 5;
  o.min_r = 0.9;
  // Still for four frames, then a jump: a line through five such points fits badly.
  for (int i = 0; i < 4; ++i) tracker.observe(i, {100, 100, 50, 50}, std::nullopt);
  tracker.observe(4, {100, 100, 50, 50}, std::nullopt);
  tracker.observe(5, {100, 200, 50, 50}, std::nullopt);
  const auto r = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 6, kImage);
  EXPECT_LT(tracker.lastCorrelation(), 0.9);
  EXPECT_EQ(tracker.activePoints(), 2);
  ASSERT_TRUE(r.has_value());
  // r^2 of a line through the last five samples is 0.5; degree 1 through (4, 100) and
  // (5, 200) gives y(6) = 300.
  EXPECT_NEAR(tracker.lastCorrelation(), std::sqrt(0.5), 1e-9);
  EXPECT_EQ(r->y, 300);
  tracker.observe(6, {100, 300, 50, 50}, std::nullopt);
  EXPECT_EQ(tracker.activePoints(), 3);
}

TEST(Tracker, EnlargementArithmetic) {
  TrackingOptions o;
  o.enlarge_px = 10;
  o.enlarge_scale = 0.2;
  o.enlarge_speed_scale = 0.01;
  const cv::Rect2d r = enlargeRegion({100, 100, 100, 50}, o, 5.0);
  // width grows by 10 + (0.2 + 0.05) * 100 = 35, height by 10 + 0.25 * 50 = 22.5, centred.
  EXPECT_DOUBLE_EQ(r.width, 135);
  EXPECT_DOUBLE_EQ(r.height, 72.5);
  EXPECT_DOUBLE_EQ(r.x + r.width / 2, 150);
  EXPECT_DOUBLE_EQ(r.y + r.height / 2, 125);
}

TEST(Tracker, ReductionRatioDampsShrinking) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  o.degree = 0;
  o.data_points = 1;
  o.reduction_percent = 10;
  tracker.observe(0, {100, 100, 200, 200}, std::nullopt);
  tracker.observe(1, {100, 100, 200, 200}, std::nullopt);
  ASSERT_TRUE(tracker.estimate(o, CameraModel{}, TargetGeometry{}, 2, kImage));
  tracker.observe(2, {150, 150, 100, 100}, std::nullopt);
  const auto r = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 3, kImage);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->width, 180, 1);  // 200 * 0.9, not 100
}

TEST(Tracker, MissRestartsFromTheNextDetection) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  for (int i = 0; i < 5; ++i) tracker.observe(i, {100.0 + i, 100, 50, 50}, std::nullopt);
  ASSERT_TRUE(tracker.estimate(o, CameraModel{}, TargetGeometry{}, 5, kImage));
  tracker.observeMiss();
  EXPECT_FALSE(tracker.estimate(o, CameraModel{}, TargetGeometry{}, 6, kImage).has_value());
  tracker.observe(7, {300, 300, 50, 50}, std::nullopt);
  // One detection: the region about it (no memory of the old track), a quarter of the box
  // wider on every side even without the options' enlargement.
  EXPECT_TRUE(tracker.fromOneDetection());
  const auto guess = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 8, kImage);
  ASSERT_TRUE(guess.has_value());
  EXPECT_EQ(*guess, cv::Rect(287, 287, 76, 76));  // 50 + 2 * 12.5 = 75, rounded outwards
  tracker.observe(8, {300, 300, 50, 50}, std::nullopt);
  EXPECT_FALSE(tracker.fromOneDetection());
  const auto r = tracker.estimate(o, CameraModel{}, TargetGeometry{}, 9, kImage);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->x, 300);  // no memory of the old track
}

TEST(Tracker, ThreeDParametersProjectTheEstimatedPose) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  o.mode = TrackingMode::Parameters3D;
  o.degree = 1;
  CameraModel cam;
  TargetGeometry target;
  for (int i = 0; i < 5; ++i) {
    Pose p;
    p.tx_mm = 10.0 * i;
    p.tz_mm = 800;
    tracker.observe(i, projectedTargetBox(cam, target, p), p);
  }
  Pose expected;
  expected.tx_mm = 50;
  expected.tz_mm = 800;
  const cv::Rect2d box = projectedTargetBox(cam, target, expected);
  const auto r = tracker.estimate(o, cam, target, 5, kImage);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->x, box.x, 1.0);
  EXPECT_NEAR(r->width, box.width, 2.0);
  // Disk of radius 50 mm at 800 mm through an 800 px focal length: 100 px wide.
  EXPECT_NEAR(box.width, 100.0, 0.5);
}

TEST(Tracker, AnglesAreUnwrappedAcrossPlusMinus180) {
  RegionTracker tracker;
  TrackingOptions o = noEnlargement();
  o.mode = TrackingMode::Parameters3D;
  o.degree = 1;
  CameraModel cam;
  TargetGeometry target;
  for (int i = 0; i < 4; ++i) {
    Pose p;
    p.rz_deg = 170.0 + 5 * i > 180 ? 170.0 + 5 * i - 360 : 170.0 + 5 * i;
    p.rx_deg = 30;
    tracker.observe(i, projectedTargetBox(cam, target, p), p);
  }
  Pose expected;
  expected.rz_deg = 190 - 360;
  expected.rx_deg = 30;
  const auto r = tracker.estimate(o, cam, target, 4, kImage);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->height, projectedTargetBox(cam, target, expected).height, 2.0);
}

}  // namespace
}  // namespace imagepro
