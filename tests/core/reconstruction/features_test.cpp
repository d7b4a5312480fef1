#include "core/reconstruction/features.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <numeric>
#include <random>

#include "core/common/simd_level.h"
#include "core/reconstruction/pose.h"
#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"
#include "core/source/virtual_renderer.h"
#include "status_print.h"
#include "test_scenes.h"
#include "support/plain_scene.h"

namespace imagepro {
namespace {

using testing::makePose;
using testing::seenRimEllipse;

struct FeatureTest : ::testing::Test {
  CameraModel cam;
  TargetGeometry target;
  VirtualSceneOptions scene = test::plainScene();
  FeatureWorkspace ws;
  cv::Mat image;
  cv::Rect crop;
  int threshold = -1;
  std::vector<Eigen::Vector2d> points;

  // Fronto-parallel target at 800 mm: its rim is a circle of 50 px about `centre`.
  Pose frontal(double rz = 10.0) { return makePose(cam, 800, 0, 0, rz, 300.3, 250.7); }
  Eigen::Vector2d centreOf(const Pose& p) { return projectIdeal(cam, translation(p)); }
  double rimRadiusPx(const Pose& p) { return cam.fu() * target.radius_mm / p.tz_mm; }

  Status prepare(const Pose& pose, const Ellipse& detected, ThresholdMethod method = ThresholdMethod::AtMod) {
    renderTarget(cam, target, scene, pose, image);
    EXPECT_EQ(targetCrop(detected, 4, image.size(), crop), Status::Ok);
    return rethresholdCrop(image, crop, {method, 128}, 128, ws, threshold);
  }
  // Signed radial deviations of the contour points from the true rim circle.
  std::vector<double> deviations(const Pose& pose) {
    std::vector<double> d;
    for (const auto& p : points) d.push_back((p - centreOf(pose)).norm() - rimRadiusPx(pose));
    return d;
  }
  static double mean(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  }
  int spotSizedComponents(const Ellipse& e) const;
  static double maxAbs(const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m = std::max(m, std::abs(x));
    return m;
  }
};

TEST(TargetCrop, IsTheEllipsesBoxWithItsMarginClippedToTheImage) {
  cv::Rect crop;
  ASSERT_EQ(targetCrop({100, 80, 30, 10, 0}, 4, {640, 480}, crop), Status::Ok);
  EXPECT_EQ(crop, cv::Rect(66, 66, 69, 29));
  ASSERT_EQ(targetCrop({100, 80, 30, 10, 45}, 0, {640, 480}, crop), Status::Ok);
  const double h = std::sqrt(0.5 * (900 + 100));  // 22.36 both ways
  EXPECT_EQ(crop.x, static_cast<int>(std::floor(100 - h)));
  EXPECT_EQ(crop.width, static_cast<int>(std::ceil(100 + h)) - crop.x + 1);
  ASSERT_EQ(targetCrop({5, 470, 30, 30, 0}, 4, {640, 480}, crop), Status::Ok);
  EXPECT_EQ(crop, cv::Rect(0, 436, 40, 44));
  EXPECT_EQ(targetCrop({-100, -100, 10, 10, 0}, 4, {640, 480}, crop), Status::OutOfImage);
  EXPECT_EQ(targetCrop({100, 100, 0, 0, 0}, 4, {640, 480}, crop), Status::OutOfImage);
  EXPECT_EQ(targetCrop({NAN, 100, 10, 10, 0}, 4, {640, 480}, crop), Status::OutOfImage);
}

TEST_F(FeatureTest, RethresholdMethods) {
  const Pose pose = frontal();
  const Ellipse e = seenRimEllipse(cam, target, pose);
  ASSERT_EQ(prepare(pose, e, ThresholdMethod::AtMod), Status::Ok);
  // Between the disk's white and the card's black.
  EXPECT_GT(threshold, scene.black_level);
  EXPECT_LT(threshold, scene.white_level);
  EXPECT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::None, 0}, 77, ws, threshold), Status::Ok);
  EXPECT_EQ(threshold, 77);
  EXPECT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::None, 0}, -1, ws, threshold),
            Status::InvalidSettings);
  EXPECT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::Manual, 99}, -1, ws, threshold), Status::Ok);
  EXPECT_EQ(threshold, 99);
  // The binary crop the pixel modes read is grey > t.
  ASSERT_EQ(extractContour(ContourMode::FullPathMod, image, crop, e, ws, points), Status::Ok);
  ASSERT_EQ(ws.binary.size(), crop.size());
  for (int y = 0; y < crop.height; y += 7)
    for (int x = 0; x < crop.width; x += 5)
      EXPECT_EQ(ws.binary.at<uchar>(y, x) != 0, image.at<uchar>(crop.y + y, crop.x + x) > 99);
  const cv::Mat flat(480, 640, CV_8UC1, cv::Scalar(128));
  EXPECT_EQ(rethresholdCrop(flat, crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold),
            Status::ThresholdUndefined);
  EXPECT_EQ(rethresholdCrop(cv::Mat(), crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold),
            Status::EmptyFrame);
  EXPECT_EQ(rethresholdCrop(flat, cv::Rect(600, 400, 100, 100), {ThresholdMethod::AtMod, 0}, -1, ws,
                            threshold),
            Status::OutOfImage);
}

// AT-Orig and AT-Mod on the crop's own histogram: what lies outside the crop (here a bright
// frame around it) does not move the crop's threshold. A near target's large crop is
// histogrammed on every k-th row; its threshold stays within a grey level of the whole
// crop's.
TEST_F(FeatureTest, RethresholdAtOrigAndAtModOnTheCrop) {
  for (double z : {1200.0, 800.0, 600.0, 500.0, 400.0}) {
    const Pose pose = makePose(cam, z, 25, 30, 10, 320, 240);
    const Ellipse e = seenRimEllipse(cam, target, pose);
    renderTarget(cam, target, scene, pose, image);
    ASSERT_EQ(targetCrop(e, 4, image.size(), crop), Status::Ok);
    cv::Mat framed(image.size(), CV_8UC1, cv::Scalar(250));
    image(crop).copyTo(framed(crop));
    Histogram whole{};
    computeHistogram(framed(crop), whole);
    for (ThresholdMethod method : {ThresholdMethod::AtOrig, ThresholdMethod::AtMod}) {
      int expected = -1;
      ASSERT_EQ(computeThreshold({method, 0}, whole, expected), Status::Ok);
      ASSERT_EQ(rethresholdCrop(framed, crop, {method, 0}, -1, ws, threshold), Status::Ok);
      EXPECT_GT(threshold, scene.black_level) << z;
      EXPECT_LT(threshold, scene.white_level) << z;
      EXPECT_EQ(threshold, expected) << z;
      // Sampled rows (the sub-pixel mode): the same on a small crop, within a grey level on
      // a large one.
      int sampled = -1;
      ASSERT_EQ(rethresholdCrop(framed, crop, {method, 0}, -1, ws, sampled, true), Status::Ok);
      if (crop.area() < 2 * kCropHistogramPixels)
        EXPECT_EQ(sampled, expected) << z;
      else
        EXPECT_NEAR(sampled, expected, 1) << z << " " << crop.area();
      // The contour and spots follow from it.
      ASSERT_EQ(extractContour(ContourMode::FullPathMod, framed, crop, e, ws, points), Status::Ok);
      SpotFeatures spots;
      EXPECT_EQ(extractSpots(framed, crop, e, target, true, ws, spots), Status::Ok);
    }
  }
}

// Full path ORG takes pixel centres: on average inside the rim. MOD puts the points on the
// pixel boundary, SubPixel on the grey level's mid-crossing.
TEST_F(FeatureTest, ContourModesAgainstTheTrueRim) {
  const Pose pose = frontal();
  const Ellipse e = seenRimEllipse(cam, target, pose);
  scene.mode = RenderMode::Binary;
  ASSERT_EQ(prepare(pose, e), Status::Ok);

  ASSERT_EQ(extractContour(ContourMode::FullPathOrg, image, crop, e, ws, points), Status::Ok);
  std::vector<double> d = deviations(pose);
  EXPECT_GT(points.size(), 250u);  // every boundary pixel once: about 4 sqrt(2) r
  EXPECT_LT(mean(d), -0.25);
  EXPECT_GT(mean(d), -0.6);
  for (const auto& p : points) EXPECT_EQ(p, p.array().round().matrix());  // pixel centres

  ASSERT_EQ(extractContour(ContourMode::FullPathMod, image, crop, e, ws, points), Status::Ok);
  d = deviations(pose);
  EXPECT_GT(points.size(), 250u);
  EXPECT_LT(std::abs(mean(d)), 0.08);
  EXPECT_LT(maxAbs(d), 0.75);

  scene.mode = RenderMode::Grey;
  ASSERT_EQ(prepare(pose, e), Status::Ok);
  // Without the rim edge model a round rim takes up to 320 points: this 50 px one crosses
  // about 2 sqrt(2) (a + b) = 283 rows and columns, and keeps them all.
  ASSERT_EQ(extractContour(ContourMode::SubPixel, image, crop, e, ws, points, false), Status::Ok);
  d = deviations(pose);
  EXPECT_GT(points.size(), 270u);
  EXPECT_LT(points.size(), 300u);
  EXPECT_LT(std::abs(mean(d)), 0.03);
  EXPECT_LT(maxAbs(d), 0.25);  // linear interpolation across a sharp anti-aliased edge
  // With it (the default), about 160, placed by the area under the sharp edge.
  ASSERT_EQ(extractContour(ContourMode::SubPixel, image, crop, e, ws, points), Status::Ok);
  d = deviations(pose);
  EXPECT_GT(points.size(), 150u);
  EXPECT_LT(points.size(), 170u);
  EXPECT_LT(std::abs(mean(d)), 0.01);
  EXPECT_LT(maxAbs(d), 0.08);

  // A 40 px rim: without the model all its 226 crossings, with it about 160.
  const Pose farther = makePose(cam, 1000, 0, 0, 10, 300.3, 250.7);
  const Ellipse eFar = seenRimEllipse(cam, target, farther);
  ASSERT_EQ(prepare(farther, eFar), Status::Ok);
  ASSERT_EQ(extractContour(ContourMode::SubPixel, image, crop, eFar, ws, points, false), Status::Ok);
  EXPECT_GT(points.size(), 215u);
  EXPECT_LT(points.size(), 235u);
  d = deviations(farther);
  EXPECT_LT(std::abs(mean(d)), 0.03);
  ASSERT_EQ(extractContour(ContourMode::SubPixel, image, crop, eFar, ws, points), Status::Ok);
  EXPECT_GT(points.size(), 145u);
  EXPECT_LT(points.size(), 170u);
  d = deviations(farther);
  EXPECT_LT(std::abs(mean(d)), 0.01);

  // Tilted 40 deg the rim is no longer near round (b = 0.77 a): of its about 249 crossings
  // a fractional line step keeps about 160 (a whole-pixel step of 1 would keep all).
  const Pose tilted = makePose(cam, 800, 40, 30, 10, 300.3, 250.7);
  const Ellipse eTilted = seenRimEllipse(cam, target, tilted);
  ASSERT_LT(eTilted.b, 0.8 * eTilted.a);
  ASSERT_EQ(prepare(tilted, eTilted), Status::Ok);
  ASSERT_EQ(extractContour(ContourMode::SubPixel, image, crop, eTilted, ws, points), Status::Ok);
  EXPECT_GT(points.size(), 140u);
  EXPECT_LT(points.size(), 180u);

  // Blur moves a threshold crossing but not the mid-level crossing.
  scene.blur_sigma_px = 1.5;
  ASSERT_EQ(prepare(pose, e), Status::Ok);
  ASSERT_EQ(extractContour(ContourMode::SubPixel, image, crop, e, ws, points), Status::Ok);
  d = deviations(pose);
  EXPECT_GT(points.size(), 100u);
  EXPECT_LT(std::abs(mean(d)), 0.05);
  EXPECT_LT(maxAbs(d), 0.2);
}

// The 8 rays at k * 45 deg; with Rz = 0 the offset spot lies on the east ray, where the
// ORG walk from the centre stops at the spot; MOD walks in from outside the rim.
TEST_F(FeatureTest, EightPointsOrgStopsAtTheOffsetSpotAndModDoesNot) {
  const Pose pose = frontal(0.0);
  const Ellipse e = seenRimEllipse(cam, target, pose);
  scene.mode = RenderMode::Binary;
  ASSERT_EQ(prepare(pose, e), Status::Ok);
  ASSERT_EQ(extractContour(ContourMode::EightPointsOrg, image, crop, e, ws, points), Status::Ok);
  ASSERT_EQ(points.size(), 8u);
  const std::vector<double> org = deviations(pose);
  EXPECT_LT(org[0], -0.4 * rimRadiusPx(pose));  // east: stopped at the offset spot's near edge
  for (int k = 1; k < 8; ++k) EXPECT_LT(std::abs(org[k]), 1.5) << k;

  ASSERT_EQ(extractContour(ContourMode::EightPointsMod, image, crop, e, ws, points), Status::Ok);
  ASSERT_EQ(points.size(), 8u);
  const std::vector<double> mod = deviations(pose);
  EXPECT_LT(maxAbs(mod), 0.75);
  for (int k = 0; k < 8; ++k) {  // on the rays
    const Eigen::Vector2d dir = (points[k] - Eigen::Vector2d(e.cx, e.cy)).normalized();
    EXPECT_NEAR(std::atan2(dir.y(), dir.x()), std::remainder(k * M_PI / 4, 2 * M_PI), 1e-9);
  }
}

// A white bar touching the rim inside the crop: full path ORG follows it, MOD stays on the rim.
TEST_F(FeatureTest, ClutterInTheCropFoolsOrgNotMod) {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(20));
  const cv::Point2d c(320.25, 240.5);
  const double r = 60;
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      if (std::hypot(x - c.x, y - c.y) < r) img.at<uchar>(y, x) = 230;
  cv::rectangle(img, cv::Point(376, 180), cv::Point(390, 300), cv::Scalar(230), cv::FILLED);
  const Ellipse e{c.x + 0.4, c.y - 0.3, r + 0.5, r - 0.2, 0};
  ASSERT_EQ(targetCrop(e, 4, img.size(), crop), Status::Ok);
  ASSERT_EQ(rethresholdCrop(img, crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold), Status::Ok);
  auto worst = [&] {
    double m = 0;
    for (const auto& p : points) m = std::max(m, std::abs((p - Eigen::Vector2d(c.x, c.y)).norm() - r));
    return m;
  };
  ASSERT_EQ(extractContour(ContourMode::FullPathOrg, img, crop, e, ws, points), Status::Ok);
  EXPECT_GT(worst(), 5.0);
  ASSERT_EQ(extractContour(ContourMode::FullPathMod, img, crop, e, ws, points), Status::Ok);
  EXPECT_LT(worst(), 0.8);
  ASSERT_EQ(extractContour(ContourMode::SubPixel, img, crop, e, ws, points), Status::Ok);
  EXPECT_LT(worst(), 0.8);
}

TEST_F(FeatureTest, TooFewPointsOnABlackCrop) {
  const cv::Mat black(480, 640, CV_8UC1, cv::Scalar(0));
  const Ellipse e{320, 240, 50, 40, 0};
  ASSERT_EQ(targetCrop(e, 4, black.size(), crop), Status::Ok);
  ASSERT_EQ(rethresholdCrop(black, crop, {ThresholdMethod::Manual, 128}, -1, ws, threshold), Status::Ok);
  for (ContourMode m : {ContourMode::EightPointsOrg, ContourMode::EightPointsMod, ContourMode::FullPathOrg,
                        ContourMode::FullPathMod, ContourMode::SubPixel})
    EXPECT_EQ(extractContour(m, black, crop, e, ws, points), Status::TooFewPoints);
}

// Spot centroids against the exact image of each spot's centre of area (the centre of the
// spot's image conic), for poses across the range.
// The crop belongs to the frame rethresholdCrop saw: a smaller frame handed to the contour
// or the spot search would be read past its rows. A build with the core's checks on stops.
TEST_F(FeatureTest, AFrameSmallerThanTheCropIsAContractViolation) {
#if defined(NDEBUG) && !defined(IMAGEPRO_CONTRACTS)
  GTEST_SKIP() << "the checks compile to nothing here (a release build without -DIMAGEPRO_CONTRACTS=ON)";
#else
  const Pose pose = frontal();
  const Ellipse e = seenRimEllipse(cam, target, pose);
  ASSERT_EQ(prepare(pose, e), Status::Ok);
  const cv::Mat smaller = image(cv::Rect(0, 0, crop.x + crop.width / 2, crop.y + crop.height / 2)).clone();
  SpotFeatures spots;
  EXPECT_DEATH(extractSpots(smaller, crop, e, target, true, ws, spots), "the crop lies inside the frame");
  EXPECT_DEATH(extractContour(ContourMode::SubPixel, smaller, crop, e, ws, points), "the crop lies inside the frame");
#endif
}

TEST_F(FeatureTest, SpotCentroidsAndIdentity) {
  for (RenderMode mode : {RenderMode::Grey, RenderMode::Binary}) {
    scene.mode = mode;
    const double tolerance = mode == RenderMode::Grey ? 0.03 : 0.2;
    for (const Pose& pose : {makePose(cam, 500, 0, 0, 0, 320, 240), makePose(cam, 800, 40, 30, 120, 250, 300),
                             makePose(cam, 1150, 55, -70, -175, 400, 200), makePose(cam, 700, 20, 90, 179.9, 350, 220)}) {
      const Ellipse e = seenRimEllipse(cam, target, pose);
      ASSERT_EQ(prepare(pose, e), Status::Ok);
      SpotFeatures spots;
      ASSERT_EQ(extractSpots(image, crop, e, target, true, ws, spots), Status::Ok);
      EXPECT_EQ(spots.candidates, 2);
      Eigen::Vector2d centre, offset;
      ASSERT_TRUE(conicMatrixCentre(imageConicOfTargetCircle(cam, pose, 0, 0, target.spot_radius_mm), centre));
      ASSERT_TRUE(conicMatrixCentre(
          imageConicOfTargetCircle(cam, pose, target.spot_offset_mm, 0, target.spot_radius_mm), offset));
      EXPECT_LT((spots.centre_spot - centre).norm(), tolerance) << pose.tz_mm;
      EXPECT_LT((spots.offset_spot - offset).norm(), tolerance) << pose.tz_mm;
    }
  }
}

// Far targets (spots 2-3 px across), blurred, noisy, lit unevenly and JPEG-compressed:
// the weighted centres lie nearer the spots' true centres than the plain centroids, by
// about a third on the real-scene frames (docs/reconstruction.md), and have no bias on a
// clean frame.
TEST_F(FeatureTest, WeightedSpotCentresBeatThePlainCentroidOnSmallNoisySpots) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> tilt(0.0, 50.0), turn(-180.0, 180.0), distance(1800.0, 2400.0);
  scene.blur_sigma_px = 0.9;
  scene.noise_sigma = 4.0;
  scene.illumination_gradient = 0.4;
  double plainSquares = 0.0, weightedSquares = 0.0;
  int measured = 0;
  for (int i = 0; i < 40; ++i) {
    const Pose pose = makePose(cam, distance(rng), tilt(rng), turn(rng), turn(rng), 250 + 3 * i, 200 + 2 * i);
    scene.seed = static_cast<std::uint64_t>(i);
    renderTarget(cam, target, scene, pose, image, static_cast<std::uint64_t>(i));
    std::vector<uchar> jpeg;
    cv::imencode(".jpg", image, jpeg, {cv::IMWRITE_JPEG_QUALITY, 60});
    image = cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE);
    const Ellipse e = seenRimEllipse(cam, target, pose);
    ASSERT_EQ(targetCrop(e, 4, image.size(), crop), Status::Ok);
    ASSERT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::AtMod, 128}, 128, ws, threshold, true), Status::Ok);
    SpotFeatures plain, weighted;
    if (extractSpots(image, crop, e, target, false, ws, plain) != Status::Ok ||
        extractSpots(image, crop, e, target, true, ws, weighted) != Status::Ok)
      continue;
    Eigen::Vector2d centre, offset;
    ASSERT_TRUE(conicMatrixCentre(imageConicOfTargetCircle(cam, pose, 0, 0, target.spot_radius_mm), centre));
    ASSERT_TRUE(conicMatrixCentre(
        imageConicOfTargetCircle(cam, pose, target.spot_offset_mm, 0, target.spot_radius_mm), offset));
    plainSquares += (plain.centre_spot - centre).squaredNorm() + (plain.offset_spot - offset).squaredNorm();
    weightedSquares += (weighted.centre_spot - centre).squaredNorm() + (weighted.offset_spot - offset).squaredNorm();
    ++measured;
  }
  ASSERT_GE(measured, 36);
  const double plainRms = std::sqrt(plainSquares / (2 * measured));
  const double weightedRms = std::sqrt(weightedSquares / (2 * measured));
  EXPECT_LT(weightedRms, 0.6 * plainRms) << weightedRms << " " << plainRms;
  EXPECT_LT(weightedRms, 0.06);

  // Clean and head-on at 2 m: both centres within 0.02 px of the truth.
  scene = test::plainScene();
  const Pose head = makePose(cam, 2000, 0, 0, 30, 310.4, 245.8);
  const Ellipse e = seenRimEllipse(cam, target, head);
  ASSERT_EQ(prepare(head, e), Status::Ok);
  SpotFeatures weighted;
  ASSERT_EQ(extractSpots(image, crop, e, target, true, ws, weighted), Status::Ok);
  Eigen::Vector2d centre, offset;
  ASSERT_TRUE(conicMatrixCentre(imageConicOfTargetCircle(cam, head, 0, 0, target.spot_radius_mm), centre));
  ASSERT_TRUE(conicMatrixCentre(imageConicOfTargetCircle(cam, head, target.spot_offset_mm, 0, target.spot_radius_mm), offset));
  EXPECT_LT((weighted.centre_spot - centre).norm(), 0.02);
  EXPECT_LT((weighted.offset_spot - offset).norm(), 0.02);
}

TEST_F(FeatureTest, SpotsNotFoundAmbiguousAndSpecksIgnored) {
  const Pose pose = makePose(cam, 700, 25, 10, 60, 330, 230);
  const Ellipse e = seenRimEllipse(cam, target, pose);
  SpotFeatures spots;
  // A plain disk.
  TargetGeometry plain = target;
  plain.spot_radius_mm = 0;
  renderTarget(cam, plain, scene, pose, image);
  ASSERT_EQ(targetCrop(e, 4, image.size(), crop), Status::Ok);
  ASSERT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold), Status::Ok);
  EXPECT_EQ(extractSpots(image, crop, e, target, true, ws, spots), Status::SpotsNotFound);
  EXPECT_EQ(spots.candidates, 0);
  // The target with single-pixel specks: still two spots.
  renderTarget(cam, target, scene, pose, image);
  for (int k = 0; k < 6; ++k) image.at<uchar>(static_cast<int>(e.cy) + 3 * k - 20, static_cast<int>(e.cx) - 25 + k) = 0;
  ASSERT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold), Status::Ok);
  EXPECT_EQ(extractSpots(image, crop, e, target, true, ws, spots), Status::Ok);
  EXPECT_EQ(spots.candidates, 2);
  // A third spot.
  cv::circle(image, cv::Point(static_cast<int>(e.cx), static_cast<int>(e.cy - 0.5 * e.b)), 6, cv::Scalar(20), cv::FILLED);
  ASSERT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold), Status::Ok);
  EXPECT_EQ(extractSpots(image, crop, e, target, true, ws, spots), Status::AmbiguousSpots);
  EXPECT_EQ(spots.candidates, 3);
}

// A dark occluder (tape, a clamp) across the disk a pixel from the offset spot: the crop's
// one cut level joins the two under blur, and the search alone takes the strip with the
// spot (a component that reaches its edge). The detection stage's local binary image
// parts them; given its spot boxes, the search takes them, and the offset
// spot's centre stays within half a pixel of the true one (the blurred strip darkens the
// edge of its box), where alone the search is off by more than 3 px.
TEST_F(FeatureTest, AnOccluderJoinedToASpotLeavesItToTheDetectionsSpots) {
  const Pose pose = makePose(cam, 700, 20, 10, 0, 330, 230);
  const Ellipse e = seenRimEllipse(cam, target, pose);
  renderTarget(cam, target, scene, pose, image);
  Eigen::Vector2d centre, offset;
  ASSERT_TRUE(conicMatrixCentre(imageConicOfTargetCircle(cam, pose, 0, 0, target.spot_radius_mm), centre));
  ASSERT_TRUE(conicMatrixCentre(
      imageConicOfTargetCircle(cam, pose, target.spot_offset_mm, 0, target.spot_radius_mm), offset));
  const double spotPx = cam.fu() * target.spot_radius_mm / pose.tz_mm;
  // The strip right of the offset spot, then the frame blurred as a lens does.
  const int stripX = static_cast<int>(std::ceil(offset.x() + spotPx + 1.0));
  cv::rectangle(image, cv::Rect(stripX, 0, 12, image.rows), cv::Scalar(60), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);
  ASSERT_EQ(targetCrop(e, 4, image.size(), crop), Status::Ok);
  ASSERT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::AtMod, 0}, -1, ws, threshold), Status::Ok);
  SpotFeatures spots;
  const Status alone = extractSpots(image, crop, e, target, true, ws, spots);
  EXPECT_TRUE(!ok(alone) || (spots.offset_spot - offset).norm() > 3.0) << alone;
  auto boxAbout = [&](const Eigen::Vector2d& p) {
    const int r = static_cast<int>(std::round(spotPx)) + 1;  // the spot and its path's ring
    return cv::Rect(static_cast<int>(std::floor(p.x())) - r, static_cast<int>(std::floor(p.y())) - r, 2 * r + 1,
                    2 * r + 1);
  };
  const std::array<cv::Rect, 2> detected{boxAbout(centre), boxAbout(offset)};
  ASSERT_EQ(extractSpots(image, crop, e, target, true, ws, spots, &detected), Status::Ok);
  EXPECT_LT((spots.centre_spot - centre).norm(), 0.05);
  EXPECT_LT((spots.offset_spot - offset).norm(), 0.5);
  // Boxes outside the crop are not taken.
  const std::array<cv::Rect, 2> outside{cv::Rect(0, 0, 5, 5), cv::Rect(10, 0, 5, 5)};
  const Status withOutside = extractSpots(image, crop, e, target, true, ws, spots, &outside);
  EXPECT_TRUE(!ok(withOutside) || (spots.offset_spot - offset).norm() > 3.0) << withOutside;
}

// The spot search's rule done plainly, for reference: the 8-connected components (OpenCV's
// labelling) of the pixels at most the middle of the class means, inside 0.85 of the
// detected ellipse row by row (ceil of the left crossing to floor of the right), whose area
// is 1/5 to 5 times a spot's expected area and which do not reach the first or last pixel
// of a row's span (what comes in from beyond the disk), unless with those there are two.
int FeatureTest::spotSizedComponents(const Ellipse& e) const {
  const double t = e.angle_deg * M_PI / 180.0, c = std::cos(t), s = std::sin(t);
  const double ia2 = 1.0 / (0.85 * 0.85 * e.a * e.a), ib2 = 1.0 / (0.85 * 0.85 * e.b * e.b);
  const double P = c * c * ia2 + s * s * ib2, Q = c * s * (ia2 - ib2), R = s * s * ia2 + c * c * ib2;
  const double level = std::clamp(std::floor(0.5 * (ws.dark_mean + ws.bright_mean)), 0.0, 255.0);
  cv::Mat dark(crop.size(), CV_8UC1, cv::Scalar(0));
  std::vector<cv::Point> span_ends;
  for (int r = 0; r < crop.height; ++r) {
    const double dy = crop.y + r - e.cy, disc = Q * Q * dy * dy - P * (R * dy * dy - 1.0);
    if (disc < 0.0) continue;
    const int x0 = std::max(static_cast<int>(std::ceil(e.cx + (-Q * dy - std::sqrt(disc)) / P)), crop.x);
    const int x1 = std::min(static_cast<int>(std::floor(e.cx + (-Q * dy + std::sqrt(disc)) / P)), crop.x + crop.width - 1);
    for (int x = x0; x <= x1; ++x)
      if (image.at<uchar>(crop.y + r, x) <= level) dark.at<uchar>(r, x - crop.x) = 255;
    if (x0 <= x1) {
      span_ends.emplace_back(x0 - crop.x, r);
      span_ends.emplace_back(x1 - crop.x, r);
    }
  }
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(dark, labels, stats, centroids, 8);
  std::vector<bool> at_limit(static_cast<std::size_t>(n), false);
  for (const cv::Point& p : span_ends)
    if (dark.at<uchar>(p) != 0) at_limit[static_cast<std::size_t>(labels.at<int>(p))] = true;
  const double expected = M_PI * std::pow(target.spot_radius_mm / target.radius_mm, 2) * e.a * e.b;
  int sized = 0, touching = 0;
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area < std::max(2.0, 0.2 * expected) || area > 5.0 * expected + 4.0) continue;
    (at_limit[i] ? touching : sized) += 1;
  }
  return sized < 2 && sized + touching == 2 ? 2 : sized;
}

// The spot search's row scan runs 32 pixels per step with AVX2 and 16 with SSE2, after a
// test of 4 rows at a time for any dark pixel: on real crops (near and far, tilted, noise,
// blur, clutter) and on crops strewn with dark specks and runs of every length, also at the
// rows' ends, both find the same components and the same centroids to the bit, and as many
// components of spot size as a plain labelling of the same pixels.
TEST_F(FeatureTest, SpotSearchAvx2AndSse2FindTheSameSpots) {
  setSimdCeiling(SimdLevel::Avx2);
  if (simdLevel() != SimdLevel::Avx2) {
    GTEST_SKIP() << "the processor has no AVX2";
  }
  scene.noise_sigma = 2.0;
  scene.blur_sigma_px = 0.6;
  scene.clutter = 6;
  std::mt19937 rng(7);
  int compared = 0, ambiguous = 0;
  for (const Pose& pose : {makePose(cam, 400, 35, 50, 20, 330, 220), makePose(cam, 400, 0, 0, 0, 320, 240),
                           makePose(cam, 650, 55, -30, 120, 250, 300), makePose(cam, 800, 20, 90, 179.9, 350, 220),
                           makePose(cam, 1200, 60, 10, -60, 420, 180)}) {
    const Ellipse e = seenRimEllipse(cam, target, pose);
    for (int specks = 0; specks <= 60; specks += 20) {
      ASSERT_EQ(prepare(pose, e), Status::Ok);
      // Dark runs 1 to 40 px long across the inner disk, some reaching its ends.
      std::uniform_real_distribution<double> u(-0.9, 0.9);
      std::uniform_int_distribution<int> length(1, 40);
      for (int k = 0; k < specks; ++k) {
        const int y = static_cast<int>(e.cy + u(rng) * e.b);
        const int x = static_cast<int>(e.cx + u(rng) * e.a);
        const int n = length(rng);
        for (int i = 0; i < n && x + i < image.cols; ++i) image.at<uchar>(y, x + i) = static_cast<uchar>(10 + k % 40);
      }
      SpotFeatures wide, narrow;
      setSimdCeiling(SimdLevel::Avx2);
      const Status wideStatus = extractSpots(image, crop, e, target, true, ws, wide);
      setSimdCeiling(SimdLevel::Sse2);
      const Status narrowStatus = extractSpots(image, crop, e, target, true, ws, narrow);
      setSimdCeiling(SimdLevel::Avx2);
      EXPECT_EQ(wideStatus, narrowStatus) << pose.tz_mm << " " << specks;
      EXPECT_EQ(wide.candidates, narrow.candidates) << pose.tz_mm << " " << specks;
      EXPECT_EQ(wide.centre_spot.x(), narrow.centre_spot.x()) << pose.tz_mm << " " << specks;
      EXPECT_EQ(wide.centre_spot.y(), narrow.centre_spot.y()) << pose.tz_mm << " " << specks;
      EXPECT_EQ(wide.offset_spot.x(), narrow.offset_spot.x()) << pose.tz_mm << " " << specks;
      EXPECT_EQ(wide.offset_spot.y(), narrow.offset_spot.y()) << pose.tz_mm << " " << specks;
      if (specks == 0) {
        EXPECT_EQ(wideStatus, Status::Ok) << pose.tz_mm;
      }
      EXPECT_EQ(wide.candidates, spotSizedComponents(e)) << pose.tz_mm << " " << specks;
      ambiguous += wideStatus == Status::AmbiguousSpots;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 20);
  EXPECT_GT(ambiguous, 0);  // the specks made components of spot size too
}

}  // namespace
}  // namespace imagepro
