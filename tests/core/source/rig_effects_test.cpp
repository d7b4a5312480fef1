// What a rig does to the target (core/source/rig_effects.h): each effect on its share of the
// stills, occluders and glare clear of the spots and where the pose puts them, glare
// saturating, dim paper as dark as stated, and nothing else of a still changed.
#include "core/source/rig_effects.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <opencv2/imgcodecs.hpp>

#include <cmath>
#include <filesystem>

#include "core/source/real_scene.h"
#include "support/test_dirs.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> greyPhotos() {
  const fs::path dir = test::freshDir("rig_effects_photos_" + std::to_string(getpid()));
  const std::string path = (dir / "grey.png").string();
  cv::imwrite(path, cv::Mat(600, 900, CV_8UC1, cv::Scalar(120)));
  return {path};
}

cv::Point2d imageOf(const CameraModel& cam, const Pose& pose, const Eigen::Vector2d& p) {
  const Eigen::Vector3d P = rotationMatrix(pose) * Eigen::Vector3d(p.x(), p.y(), 0) + translation(pose);
  const Eigen::Vector2d q = distortPixel(cam, projectIdeal(cam, P));
  return {q.x(), q.y()};
}

TEST(RigEffects, EachEffectOnItsShareClearOfTheSpots) {
  const TargetGeometry target;
  const int n = 1000;
  int occluded = 0, glare = 0, dim = 0, tape = 0;
  for (int i = 0; i < n; ++i) {
    SceneRandom random(mixSeed(5, static_cast<std::uint64_t>(i)));
    const RigDraw d = drawRigEffects(kWebcamRigEffects, target, 130.0, random);
    const Eigen::Vector2d spots[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d(target.spot_offset_mm, 0.0)};
    if (d.occluder.present) {
      ++occluded;
      const Occluder& o = d.occluder;
      EXPECT_GE(o.width_mm, 10.0);
      EXPECT_LE(o.width_mm, 25.0);
      EXPECT_TRUE((o.level >= 15 && o.level <= 60) || (o.level >= 70 && o.level <= 160)) << o.level;
      for (const auto& s : spots)
        EXPECT_GE(distanceToSegment(s, o.from, o.to), 0.5 * o.width_mm + target.spot_radius_mm + 1.0 - 1e-9);
      // It crosses the rim: one end inside the disk or its middle line cuts it, the other far outside.
      EXPECT_LT(distanceToSegment(Eigen::Vector2d::Zero(), o.from, o.to), target.radius_mm);
      EXPECT_GT(std::max(o.from.norm(), o.to.norm()), 100.0);
      tape += o.from.norm() > target.radius_mm;
    }
    if (d.glare.present) {
      ++glare;
      const Glare& g = d.glare;
      EXPECT_GE(g.diameter_mm, 4.0);
      EXPECT_LE(g.diameter_mm, 12.0);
      EXPECT_LE(g.centre.norm() + 0.5 * g.diameter_mm, target.radius_mm);
      for (const auto& s : spots) EXPECT_GE((g.centre - s).norm(), 0.5 * g.diameter_mm + target.spot_radius_mm);
      EXPECT_GE(g.strength, 1.2 * 255.0);
    }
    if (d.dim) {
      ++dim;
      EXPECT_GE(d.dim_white, 70);
      EXPECT_LE(d.dim_white, 120);
    }
  }
  EXPECT_NEAR(occluded / double(n), 0.5, 0.05);
  EXPECT_NEAR(glare / double(n), 0.3, 0.05);
  EXPECT_NEAR(dim / double(n), 0.3, 0.05);
  EXPECT_NEAR(tape / double(occluded), 0.5, 0.08);  // tape and clamps alike
  SceneRandom none(1);
  const RigDraw nothing = drawRigEffects(RigEffects{}, target, 130.0, none);
  EXPECT_FALSE(nothing.occluder.present || nothing.glare.present || nothing.dim);
}

// The occluder covers the image of its strip's middle with its own grey, the glare saturates
// the image of its centre, and everything beyond both stays as the plain scene has it.
TEST(RigEffects, PaintedWhereThePoseProjectsThem) {
  CameraModel cam;
  cam.distortion = kThesisCameraDistortion;
  const Pose pose{10.0, -20.0, 30.0, 15.0, -10.0, 700.0};
  RigDraw d;
  d.occluder = {true, Eigen::Vector2d(30.0, -30.0), Eigen::Vector2d(120.0, -120.0), 16.0, 40};
  d.glare = {true, Eigen::Vector2d(-20.0, 20.0), 10.0, 400.0};
  const cv::Mat plain(cam.height, cam.width, CV_32FC1, cv::Scalar(200.0f));
  cv::Mat scene = plain.clone();
  paintRigEffects(d, cam, pose, scene);
  const cv::Point2d strip = imageOf(cam, pose, Eigen::Vector2d(60.0, -60.0));
  EXPECT_NEAR(scene.at<float>(cvRound(strip.y), cvRound(strip.x)), 40.0f, 1e-3);
  const cv::Point2d glare = imageOf(cam, pose, d.glare.centre);
  EXPECT_GT(scene.at<float>(cvRound(glare.y), cvRound(glare.x)), 255.0f + 150.0f);
  const cv::Point2d away = imageOf(cam, pose, Eigen::Vector2d(-40.0, -40.0));
  EXPECT_EQ(scene.at<float>(cvRound(away.y), cvRound(away.x)), 200.0f);
  // Nothing to paint leaves the scene as it was.
  cv::Mat untouched = plain.clone();
  paintRigEffects(RigDraw{}, cam, pose, untouched);
  EXPECT_EQ(cv::norm(untouched, plain, cv::NORM_INF), 0.0);
}

// A webcam set keeps every other draw of the plain set: the same poses, photographs and
// conditions, seed for seed; dim stills have the paper's stated level.
TEST(RigEffects, AWebcamSetKeepsThePlainSetsDraws) {
  Settings s;
  const RealScenes plain(s, greyPhotos()), webcam(s, greyPhotos(), kWebcamRigEffects);
  std::string error;
  int effects = 0;
  for (int i = 0; i < 12; ++i) {
    RealSceneFrame a, b;
    ASSERT_TRUE(plain.still(3, i, true, a, error)) << error;
    ASSERT_TRUE(webcam.still(3, i, true, b, error)) << error;
    ASSERT_TRUE(a.truth && b.truth);
    EXPECT_EQ(a.truth->tz_mm, b.truth->tz_mm);
    EXPECT_EQ(a.truth->rx_deg, b.truth->rx_deg);
    EXPECT_EQ(a.conditions.jpeg_quality, b.conditions.jpeg_quality);
    EXPECT_FALSE(a.rig.occluder.present || a.rig.glare.present || a.rig.dim);
    if (b.rig.dim) {
      EXPECT_EQ(b.look.white, b.rig.dim_white);
      EXPECT_LE(b.look.white, 120);
    } else {
      EXPECT_EQ(b.look.white, a.look.white);
    }
    const bool any = b.rig.occluder.present || b.rig.glare.present || b.rig.dim;
    effects += any;
    if (!any) EXPECT_EQ(cv::norm(a.image, b.image, cv::NORM_INF), 0.0) << i;
    else EXPECT_GT(cv::norm(a.image, b.image, cv::NORM_INF), 20.0) << i;
  }
  EXPECT_GT(effects, 3);
  // A negative shows no effect: there is no target for it to touch.
  RealSceneFrame negative;
  ASSERT_TRUE(webcam.still(3, 0, false, negative, error)) << error;
  EXPECT_FALSE(negative.rig.occluder.present || negative.rig.glare.present || negative.rig.dim);
}

}  // namespace
}  // namespace imagepro
