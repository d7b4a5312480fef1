// Real-scene frames (core/source/real_scene.h): the truth is the pose the target was
// drawn at (the disk is where the pose projects it, the photograph shows exactly
// around the card), the draws are reproducible and inside the stated ranges, and
// each imaging condition does what it says.
#include "core/source/real_scene.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>

#include "core/source/real_scene_video.h"
#include "core/source/virtual_renderer.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

// A photograph-like background: smooth shading with a few bright and dark shapes.
cv::Mat texturedBackground(cv::Size size, int seed) {
  cv::Mat bg(size, CV_8UC1);
  for (int v = 0; v < size.height; ++v)
    for (int u = 0; u < size.width; ++u)
      bg.at<std::uint8_t>(v, u) = static_cast<std::uint8_t>(90 + 40 * std::sin(0.02 * u + seed) * std::cos(0.015 * v));
  cv::circle(bg, {size.width / 4, size.height / 3}, 40, cv::Scalar(220), -1);
  cv::rectangle(bg, cv::Rect(size.width / 2, size.height / 2, 120, 60), cv::Scalar(15), -1);
  return bg;
}

// Three such photographs as files, so the tests need no installed package. A folder per
// process: ctest runs the tests of this file in parallel, and each one makes them anew.
std::vector<std::string> syntheticPhotos() {
  const fs::path dir = test::freshDir("real_scene_photos_" + std::to_string(getpid()));
  std::vector<std::string> paths;
  for (int i = 0; i < 3; ++i) {
    const std::string path = (dir / ("photo" + std::to_string(i) + (i == 2 ? ".jpg" : ".png"))).string();
    cv::imwrite(path, texturedBackground(cv::Size(500 + 100 * i, 400), i));
    paths.push_back(path);
  }
  return paths;
}

cv::Point2d imageOf(const CameraModel& cam, const Pose& pose, double x, double y) {
  const Eigen::Vector3d P = rotationMatrix(pose) * Eigen::Vector3d(x, y, 0) + translation(pose);
  const Eigen::Vector2d p = distortPixel(cam, projectIdeal(cam, P));
  return {p.x(), p.y()};
}

// The tilt of the target's normal from its line of sight, degrees.
double tiltDeg(const Pose& pose) {
  const Eigen::Vector3d n = rotationMatrix(pose).col(2);
  const Eigen::Vector3d sight = translation(pose).normalized();
  return std::acos(std::clamp(n.dot(sight), -1.0, 1.0)) * 180.0 / M_PI;
}

Settings thesisLens() {
  Settings s;
  s.camera().distortion = kThesisCameraDistortion;
  return s;
}

TEST(RealScene, PoseAlongRayPutsTheCentreOnThePixelAtTheDistanceAndTilt) {
  const CameraModel cam;
  for (const double tilt : {0.0, 25.0, 60.0}) {
    const Pose pose = poseAlongRay(cam, Eigen::Vector2d(100.0, 400.0), 1500.0, tilt, 37.0, -120.0);
    const Eigen::Vector2d c = projectIdeal(cam, translation(pose));
    EXPECT_NEAR(c.x(), 100.0, 1e-9);
    EXPECT_NEAR(c.y(), 400.0, 1e-9);
    EXPECT_NEAR(translation(pose).norm(), 1500.0, 1e-9);
    EXPECT_NEAR(tiltDeg(pose), tilt, 1e-9);
  }
}

// The disk in a frame without conditions: its outline fits the ellipse of the rim
// the truth pose projects (through the thesis lens), the spots are dark where the pose
// puts them, the paper white between.
TEST(RealScene, TheTargetIsWhereTheTruthPoseProjectsIt) {
  const Settings s = thesisLens();
  const cv::Mat bg = texturedBackground({640, 480}, 1) * 0.4;  // dark, so the disk stands out alone
  const TargetLook look{220, 25, 130.0};
  const Pose poses[] = {poseAlongRay(s.camera(), {320, 240}, 600, 0, 0, 30),
                        poseAlongRay(s.camera(), {180, 330}, 900, 50, 70, -100),
                        poseAlongRay(s.camera(), {470, 150}, 1300, 35, 200, 170)};
  for (const Pose& pose : poses) {
    ASSERT_TRUE(cardInFrame(s.camera(), s.target, look.card_size_mm, pose, 2.0));
    cv::Mat scene;
    composeTarget(bg, s.camera(), s.target, look, pose, scene);
    cv::Mat binary;
    cv::threshold(scene, binary, 0.5 * (look.white + look.black), 255, cv::THRESH_BINARY);
    binary.convertTo(binary, CV_8U);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(binary, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    ASSERT_FALSE(contours.empty());
    const auto& disk = *std::max_element(contours.begin(), contours.end(),
                                         [](const auto& a, const auto& b) { return a.size() < b.size(); });
    std::vector<cv::Point2f> rim;
    for (int k = 0; k < 360; ++k) {
      const double a = k * M_PI / 180.0;
      rim.push_back(imageOf(s.camera(), pose, s.target.radius_mm * std::cos(a), s.target.radius_mm * std::sin(a)));
    }
    const cv::RotatedRect seen = cv::fitEllipse(disk);
    const cv::RotatedRect truth = cv::fitEllipse(rim);
    EXPECT_LT(cv::norm(seen.center - truth.center), 0.1) << "pose tz " << pose.tz_mm;
    // The outline runs through the outermost white pixel centres: about half a pixel in.
    EXPECT_NEAR(std::max(seen.size.width, seen.size.height), std::max(truth.size.width, truth.size.height), 1.5);
    EXPECT_NEAR(std::min(seen.size.width, seen.size.height), std::min(truth.size.width, truth.size.height), 1.5);
    const auto at = [&](cv::Point2d p) { return scene.at<float>(cvRound(p.y), cvRound(p.x)); };
    EXPECT_LT(at(imageOf(s.camera(), pose, 0, 0)), look.black + 5);
    EXPECT_LT(at(imageOf(s.camera(), pose, s.target.spot_offset_mm, 0)), look.black + 5);
    EXPECT_GT(at(imageOf(s.camera(), pose, -s.target.spot_offset_mm, 0)), look.white - 5);
    EXPECT_LT(at(imageOf(s.camera(), pose, 0, 0.5 * (s.target.radius_mm + 65.0))), look.black + 5);  // the card
  }
}

// Beyond the card the photograph shows unchanged; on it, not at all.
TEST(RealScene, ThePhotographShowsExactlyAroundTheCard) {
  const Settings s;
  const cv::Mat bg = texturedBackground({640, 480}, 2);
  const TargetLook look{200, 30, 130.0};
  const Pose pose = poseAlongRay(s.camera(), {330, 250}, 700, 30, 10, 20);
  cv::Mat scene;
  composeTarget(bg, s.camera(), s.target, look, pose, scene);
  cv::Mat card = cv::Mat::zeros(bg.size(), CV_8UC1);
  std::vector<cv::Point> corners;
  for (const auto& [x, y] : {std::pair{-65, -65}, {65, -65}, {65, 65}, {-65, 65}})
    corners.push_back(imageOf(s.camera(), pose, x, y));
  cv::fillConvexPoly(card, corners, cv::Scalar(255));
  cv::Mat near_card, inside;
  cv::dilate(card, near_card, cv::Mat(), {-1, -1}, 2);
  cv::erode(card, inside, cv::Mat(), {-1, -1}, 2);
  cv::Mat photo;
  bg.convertTo(photo, CV_32F);
  cv::Mat difference = cv::abs(scene - photo);
  double worst = 0;
  cv::minMaxLoc(difference, nullptr, &worst, nullptr, nullptr, ~near_card);
  EXPECT_EQ(worst, 0.0);
  // On the card only the target's own two levels (and the grey of its edges).
  cv::Mat other_bg = 255 - bg;
  cv::Mat scene2;
  composeTarget(other_bg, s.camera(), s.target, look, pose, scene2);
  cv::minMaxLoc(cv::abs(scene - scene2), nullptr, &worst, nullptr, nullptr, inside);
  EXPECT_EQ(worst, 0.0);
}

TEST(RealScene, StillsAreReproducibleAndVaryWithTheSeed) {
  const RealScenes scenes(thesisLens(), syntheticPhotos());
  RealSceneFrame a, b, c;
  std::string error;
  ASSERT_TRUE(scenes.still(7, 3, true, a, error)) << error;
  ASSERT_TRUE(scenes.still(7, 3, true, b, error)) << error;
  ASSERT_TRUE(scenes.still(8, 3, true, c, error)) << error;
  EXPECT_EQ(cv::norm(a.image, b.image, cv::NORM_INF), 0.0);
  ASSERT_TRUE(a.truth && c.truth);
  EXPECT_NE(a.truth->tz_mm, c.truth->tz_mm);
  EXPECT_EQ(scenes.stillPose(7, 3).tz_mm, a.truth->tz_mm);
  // Its negative: the same photograph and conditions, no target.
  RealSceneFrame negative;
  ASSERT_TRUE(scenes.still(7, 3, false, negative, error)) << error;
  EXPECT_FALSE(negative.truth);
  EXPECT_EQ(negative.background, a.background);
  EXPECT_EQ(negative.conditions.jpeg_quality, a.conditions.jpeg_quality);
  EXPECT_GT(cv::norm(a.image, negative.image, cv::NORM_INF), 100.0);  // where the target was
}

// A painter draws something else at the very pose, over the same photograph, through the
// same conditions: one that draws nothing gives the negative; one that draws a flat grey
// patch differs only around the target; the truth stays the still's pose.
TEST(RealScene, APainterDrawsInTheTargetsPlace) {
  const RealScenes scenes(thesisLens(), syntheticPhotos());
  std::string error;
  RealSceneFrame target, nothing, negative, patch;
  ASSERT_TRUE(scenes.still(7, 4, true, target, error)) << error;
  ASSERT_TRUE(scenes.still(7, 4, false, negative, error)) << error;
  const ScenePainter none = [](const cv::Mat& bg, const Pose&, const TargetLook&, cv::Mat& scene) {
    bg.convertTo(scene, CV_32F);
  };
  ASSERT_TRUE(scenes.still(7, 4, true, nothing, error, none)) << error;
  ASSERT_TRUE(nothing.truth && target.truth);
  EXPECT_EQ(nothing.truth->tz_mm, target.truth->tz_mm);
  EXPECT_EQ(nothing.background, target.background);
  EXPECT_EQ(cv::norm(nothing.image, negative.image, cv::NORM_INF), 0.0);
  // A 9x9 patch of the look's white at the image of the target's centre, through composeOver.
  const Settings& s = scenes.settings();
  cv::Point centre;
  const ScenePainter square = [&](const cv::Mat& bg, const Pose& pose, const TargetLook& look, cv::Mat& scene) {
    centre = imageOf(s.camera(), pose, 0, 0);
    composeOver(
        bg,
        [&](int level, cv::Mat& out) {
          out = cv::Mat(bg.size(), CV_8UC1, cv::Scalar(level));
          out(cv::Rect(centre.x - 4, centre.y - 4, 9, 9)).setTo(look.white);
        },
        scene);
  };
  ASSERT_TRUE(scenes.still(7, 4, true, patch, error, square)) << error;
  cv::Mat differs;
  cv::compare(cv::abs(cv::Mat_<int>(patch.image) - cv::Mat_<int>(negative.image)), 40, differs, cv::CMP_GT);
  const cv::Rect near(centre.x - 12, centre.y - 12, 25, 25);  // the patch and its blur
  EXPECT_GT(cv::countNonZero(differs(near)), 40);
  differs(near).setTo(0);
  EXPECT_EQ(cv::countNonZero(differs), 0);
}

TEST(RealScene, StillsKeepToTheirRanges) {
  const Settings s = thesisLens();
  const RealScenes scenes(s, syntheticPhotos());
  int moving = 0;
  const int n = 300;
  for (int i = 0; i < n; ++i) {
    const Pose pose = scenes.stillPose(11, i);
    EXPECT_TRUE(cardInFrame(s.camera(), s.target, s.virtual_scene.card_size_mm, pose, 2.0)) << i;
    EXPECT_TRUE(targetInView(s.camera(), s.target, pose)) << i;
    EXPECT_GE(translation(pose).norm(), 400.0 - 1e-9);
    EXPECT_LE(translation(pose).norm(), 2500.0 + 1e-9);
    EXPECT_LE(tiltDeg(pose), 60.0 + 1e-9);
    SceneRandom random(mixSeed(11, static_cast<std::uint64_t>(i)));
    const SceneConditions c = randomStillConditions(random);
    EXPECT_LE(c.light_amplitude, 0.4);
    EXPECT_GE(c.blur_sigma_px, 0.5);
    EXPECT_LE(c.blur_sigma_px, 1.6);
    EXPECT_TRUE(c.motion_blur_px == 0.0 || (c.motion_blur_px >= 2.0 && c.motion_blur_px <= 6.0));
    moving += c.motion_blur_px > 0.0;
    EXPECT_GE(c.noise_sigma, 1.0);
    EXPECT_LE(c.noise_sigma, 6.0);
    EXPECT_GE(c.jpeg_quality, 40);
    EXPECT_LE(c.jpeg_quality, 95);
  }
  EXPECT_NEAR(static_cast<double>(moving) / n, 1.0 / 3.0, 0.08);
}

TEST(SceneConditions, LightRampSpansPlusMinusItsAmplitudeTowardsItsDirection) {
  SceneConditions c;
  c.light_amplitude = 0.4;
  c.light_direction_deg = 0.0;  // brightest to the right
  cv::Mat f;
  lightField(c, {640, 480}, f);
  EXPECT_NEAR(f.at<float>(240, 639), 1.4, 1e-5);
  EXPECT_NEAR(f.at<float>(240, 0), 0.6, 1e-5);
  c.light_direction_deg = 135.0;  // towards bottom-left
  c.light_gain = 0.9;
  lightField(c, {640, 480}, f);
  double lo, hi;
  cv::Point lo_at, hi_at;
  cv::minMaxLoc(f, &lo, &hi, &lo_at, &hi_at);
  EXPECT_NEAR(hi, 0.9 * 1.4, 1e-5);
  EXPECT_NEAR(lo, 0.9 * 0.6, 1e-5);
  EXPECT_EQ(hi_at, cv::Point(0, 479));
  EXPECT_EQ(lo_at, cv::Point(639, 0));
}

TEST(SceneConditions, VignetteIsBrightestAtItsCentre) {
  SceneConditions c;
  c.light_shape = LightShape::Vignette;
  c.light_amplitude = 0.3;
  c.light_centre_u = 0.25;
  c.light_centre_v = 0.75;
  cv::Mat f;
  lightField(c, {641, 481}, f);
  double lo, hi;
  cv::Point lo_at, hi_at;
  cv::minMaxLoc(f, &lo, &hi, &lo_at, &hi_at);
  EXPECT_NEAR(hi, 1.3, 1e-5);
  EXPECT_EQ(hi_at, cv::Point(160, 360));
  EXPECT_NEAR(lo, 0.7, 1e-5);
  EXPECT_EQ(lo_at, cv::Point(640, 0));
}

TEST(SceneConditions, MotionKernelIsACentredStreakOfItsLength) {
  for (const double length : {2.0, 4.5, 6.0}) {
    for (const double angle : {0.0, 30.0, 90.0, 145.0}) {
      const cv::Mat k = motionKernel(length, angle);
      ASSERT_EQ(k.rows % 2, 1);
      EXPECT_NEAR(cv::sum(k)[0], 1.0, 1e-6);
      const double c = 0.5 * (k.cols - 1), a = angle * M_PI / 180.0;
      double mu = 0, mv = 0, along2 = 0, across2 = 0;
      for (int v = 0; v < k.rows; ++v) {
        for (int u = 0; u < k.cols; ++u) {
          const double w = k.at<float>(v, u), du = u - c, dv = v - c;
          mu += w * du;
          mv += w * dv;
          along2 += w * std::pow(du * std::cos(a) + dv * std::sin(a), 2);
          across2 += w * std::pow(-du * std::sin(a) + dv * std::cos(a), 2);
        }
      }
      EXPECT_NEAR(mu, 0.0, 1e-5);  // a blurred shape keeps its centroid
      EXPECT_NEAR(mv, 0.0, 1e-5);
      // A uniform streak of length L has variance L^2 / 12 along it; splitting a sample
      // over its four pixels adds f (1 - f) <= 1/4 px^2 in either direction.
      EXPECT_NEAR(along2, length * length / 12.0, 0.25);
      EXPECT_LT(across2, 0.25);
    }
  }
}

TEST(SceneConditions, EachConditionChangesTheFrameAsItShould) {
  cv::Mat base(200, 200, CV_32FC1, cv::Scalar(60));
  base(cv::Rect(100, 0, 100, 200)).setTo(180);  // a vertical step edge at u = 99.5
  const auto apply = [&](const SceneConditions& c) {
    cv::Mat scene = base.clone(), out;
    applyConditions(scene, c, out);
    return out;
  };
  const cv::Mat clean = apply({});
  cv::Mat expected;
  base.convertTo(expected, CV_8U);
  EXPECT_EQ(cv::norm(clean, expected, cv::NORM_INF), 0.0);  // no condition: the scene itself
  const auto edgeWidth = [](const cv::Mat& img) {  // pixels of the row between the levels
    int n = 0;
    for (int u = 0; u < img.cols; ++u) n += img.at<std::uint8_t>(100, u) > 65 && img.at<std::uint8_t>(100, u) < 175;
    return n;
  };
  EXPECT_EQ(edgeWidth(clean), 0);
  SceneConditions blur;
  blur.blur_sigma_px = 1.5;
  EXPECT_GE(edgeWidth(apply(blur)), 4);
  SceneConditions across;  // a streak across the edge widens it, one along it does not
  across.motion_blur_px = 6.0;
  EXPECT_GE(edgeWidth(apply(across)), 5);
  SceneConditions along = across;
  along.motion_direction_deg = 90.0;
  EXPECT_EQ(edgeWidth(apply(along)), 0);
  SceneConditions noisy;
  noisy.noise_sigma = 4.0;
  noisy.noise_seed = 5;
  cv::Mat diff;
  cv::subtract(apply(noisy), clean, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, sd;
  cv::meanStdDev(diff, mean, sd);
  EXPECT_NEAR(sd[0], 4.0, 0.2);
  EXPECT_NEAR(mean[0], 0.0, 0.1);
  SceneConditions light;
  light.light_amplitude = 0.25;
  const cv::Mat lit = apply(light);
  EXPECT_NEAR(lit.at<std::uint8_t>(100, 0), 60 * 0.75, 1.0);
  EXPECT_NEAR(lit.at<std::uint8_t>(100, 199), 180 * 1.25, 1.0);
  // JPEG: a noisy frame changes, the more so the lower the quality.
  SceneConditions good = noisy, poor = noisy;
  good.jpeg_quality = 95;
  poor.jpeg_quality = 40;
  const double e_good = cv::norm(apply(good), apply(noisy), cv::NORM_L2);
  const double e_poor = cv::norm(apply(poor), apply(noisy), cv::NORM_L2);
  EXPECT_GT(e_good, 0.0);
  EXPECT_GT(e_poor, 1.5 * e_good);
}

TEST(RealSceneVideo, MovesSmoothlyInRangeAndHidesTheTargetInTheMiddle) {
  const Settings s;
  const RealScenes scenes(s, syntheticPhotos());
  const RealSceneVideo video(scenes, 4, 150);
  EXPECT_EQ(video.hiddenBegin(), 69);
  EXPECT_EQ(video.hiddenEnd(), 81);
  Pose previous = video.poseAt(0);
  for (int i = 0; i < video.frames(); ++i) {
    const Pose pose = video.poseAt(i);
    EXPECT_TRUE(cardInFrame(s.camera(), s.target, s.virtual_scene.card_size_mm, pose, 2.0)) << i;
    EXPECT_GE(translation(pose).norm(), 400.0 - 1e-6);
    EXPECT_LE(translation(pose).norm(), 1400.0 + 1e-6);
    EXPECT_LT((translation(pose) - translation(previous)).norm(), 40.0) << i;  // at most 1 m/s
    EXPECT_LT(rotationAngleBetweenDeg(rotationMatrix(pose), rotationMatrix(previous)), 6.0) << i;
    previous = pose;
    const SceneConditions c = video.conditionsAt(i);
    cv::Mat light;
    lightField(c, {640, 480}, light);
    double lo, hi;
    cv::minMaxLoc(light, &lo, &hi);
    EXPECT_GE(lo, 0.7 - 1e-6);
    EXPECT_LE(hi, 1.3 + 1e-6);
    EXPECT_EQ(c.jpeg_quality, 75);
  }
  RealSceneFrame frame;
  std::string error;
  ASSERT_TRUE(video.frame(75, frame, error)) << error;
  EXPECT_FALSE(frame.truth);
  ASSERT_TRUE(video.frame(10, frame, error)) << error;
  ASSERT_TRUE(frame.truth);
  EXPECT_EQ(frame.truth->tz_mm, video.poseAt(10).tz_mm);
  EXPECT_EQ(frame.image.size(), cv::Size(640, 480));
}

TEST(BackgroundPhotos, FittedToTheCameraAndListedInOrder) {
  const std::vector<std::string> photos = syntheticPhotos();
  EXPECT_EQ(listBackgrounds(fs::path(photos[0]).parent_path().string()), photos);
  EXPECT_TRUE(listBackgrounds("/no/such/folder").empty());
  const cv::Mat photo = texturedBackground({300, 100}, 0);
  const cv::Mat fitted = fitBackground(photo, {640, 480}, 1.0, 0.5, 0.5);
  EXPECT_EQ(fitted.size(), cv::Size(640, 480));
  EXPECT_EQ(fitted.type(), CV_8UC1);
  PhotoCache cache;
  cv::Mat grey;
  std::string error;
  EXPECT_FALSE(cache.load("/no/such/photo.png", grey, error));
  EXPECT_NE(error.find("/no/such/photo.png"), std::string::npos);
  ASSERT_TRUE(cache.load(photos[2], grey, error)) << error;
  EXPECT_EQ(grey.size(), cv::Size(700, 400));
}

// The installed photographs, when there are any, give frames of the camera's size.
TEST(BackgroundPhotos, DefaultFolderGivesFrames) {
  const std::string dir = defaultBackgroundsDir();
  std::vector<std::string> photos = listBackgrounds(dir);
  if (photos.empty())
    GTEST_SKIP() << "no photographs in " << dir << " (install opencv-doc, or set IMAGEPRO_BACKGROUNDS)";
  const RealScenes scenes(Settings{}, std::move(photos));
  RealSceneFrame frame;
  std::string error;
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(scenes.still(1, i, true, frame, error)) << error;
    EXPECT_EQ(frame.image.size(), cv::Size(640, 480));
  }
}

}  // namespace
}  // namespace imagepro
