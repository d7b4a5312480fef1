#include "core/reconstruction/rim_edge.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <span>

#include <opencv2/imgproc.hpp>

#include "core/ellipse/direct_fit.h"
#include "core/reconstruction/pose.h"
#include "core/source/virtual_renderer.h"
#include "status_print.h"
#include "test_scenes.h"

namespace imagepro {
namespace {

using testing::makePose;
using testing::seenRimEllipse;

// The rim's points against the exact image of the rim the renderer drew (no lens
// distortion): their signed first-order distances, positive outside.
struct RimFit {
  double mean_px = 0.0, rms_px = 0.0;
  double axis_ratio = 0.0;  // of the ellipse fitted to the points
  std::size_t points = 0;
  std::size_t off = 0;  // points further than a quarter of a pixel from the rim
};

struct RimEdgeTest : ::testing::Test {
  CameraModel cam;
  TargetGeometry target;
  VirtualSceneOptions scene;
  FeatureWorkspace ws;
  cv::Mat image;
  std::vector<Eigen::Vector2d> points;

  RimEdgeTest() { scene.mode = RenderMode::Grey; }

  cv::Mat smear;  // when set, filtered over the rendered frame (motion blur)
  std::function<void(cv::Mat&)> touch;  // when set, draws on the rendered frame before the smear

  // The sub-pixel rim of the target at `pose`, with or without the model (whose result
  // goes to `fit` when given).
  RimFit rim(const Pose& pose, bool model, RimEdgeFit* fit = nullptr) {
    renderTarget(cam, target, scene, pose, image);
    if (touch) touch(image);
    if (!smear.empty()) cv::filter2D(image, image, -1, smear, cv::Point(-1, -1), 0.0, cv::BORDER_REPLICATE);
    const Ellipse detected = seenRimEllipse(cam, target, pose);
    cv::Rect crop;
    int threshold = -1;
    EXPECT_EQ(targetCrop(detected, 4, image.size(), crop), Status::Ok);
    EXPECT_EQ(rethresholdCrop(image, crop, {ThresholdMethod::AtMod, 128}, 128, ws, threshold, true), Status::Ok);
    EXPECT_EQ(extractContour(ContourMode::SubPixel, image, crop, detected, ws, points, model && !fit), Status::Ok);
    if (model && fit) *fit = modelRimEdge(image, detected, ws, points);
    return measure(pose);
  }

  RimFit measure(const Pose& pose) const {
    const Eigen::Matrix3d C = imageConicOfTargetCircle(cam, pose, 0.0, 0.0, target.radius_mm);
    // The conic's sign: negative inside (at the rim's centre).
    const Eigen::Vector2d centre = projectIdeal(cam, translation(pose));
    const Eigen::Vector3d c(centre.x(), centre.y(), 1.0);
    const double sign = c.dot(C * c) < 0.0 ? 1.0 : -1.0;
    RimFit f;
    f.points = points.size();
    double sum = 0.0, sum2 = 0.0;
    for (const Eigen::Vector2d& p : points) {
      const Eigen::Vector3d h(p.x(), p.y(), 1.0);
      const Eigen::Vector3d g = C * h;
      const double d = sign * h.dot(g) / (2.0 * g.head<2>().norm());
      sum += d;
      sum2 += d * d;
      if (std::abs(d) > 0.25) ++f.off;
    }
    f.mean_px = sum / points.size();
    f.rms_px = std::sqrt(sum2 / points.size());
    EllipseFit fit;
    fitEllipseDirect(std::span<const Eigen::Vector2d>(points), fit);
    f.axis_ratio = fit.ellipse.b / fit.ellipse.a;
    return f;
  }

  double trueAxisRatio(const Pose& pose) const {
    const Ellipse e = seenRimEllipse(cam, target, pose);
    return e.b / e.a;
  }
};

void print(const char* what, const RimFit& own, const RimFit& model) {
  std::printf("%s: own plateaus mean %+.4f px, RMS %.4f px, b/a %.5f; rim edge model mean %+.4f px, RMS %.4f px, "
              "b/a %.5f\n",
              what, own.mean_px, own.rms_px, own.axis_ratio, model.mean_px, model.rms_px, model.axis_ratio);
}

// A far target tilted 55 deg in front of a bright scene: the card shows only about 3 px
// beyond the rim's flat sides, and at blur 1.4 px the scene's light reaches the rim's own
// plateaus there. The model's levels, fitted over the whole rim, leave those probes out.
TEST_F(RimEdgeTest, FarTiltedRimOverABrightSceneKeepsItsShape) {
  scene.blur_sigma_px = 1.4;
  scene.background_level = 200;
  const Pose pose = makePose(cam, 2200, 55, 20, 10, 360.3, 270.7);
  const RimFit own = rim(pose, false), model = rim(pose, true);
  const double truth = trueAxisRatio(pose);
  print("far, 55 deg", own, model);
  std::printf("true b/a %.5f\n", truth);
  EXPECT_EQ(own.points, model.points);
  EXPECT_LT(model.rms_px, 0.55 * own.rms_px);
  EXPECT_LT(std::abs(model.axis_ratio - truth), 0.4 * std::abs(own.axis_ratio - truth));
}

// A grey clamp lying over the card beside a sixth of the rim (grey 130 for the card's
// black), then blurred with the frame: there the edge runs from the paper to the clamp, and
// the planes' mid-level, between the paper and the card, lies further out on that arc. The
// model leaves those crossings out.
TEST_F(RimEdgeTest, ACrossingBesideAClampIsLeftOut) {
  scene.blur_sigma_px = 0.0;
  const Pose pose = makePose(cam, 1200, 15, 30, 10, 320.3, 240.7);
  const Ellipse e = seenRimEllipse(cam, target, pose);
  const double th = e.angle_deg * M_PI / 180.0;
  // Pixels beyond the rim within 0.5 of its radius, and within 30 deg of its major axis's
  // end (in the frame where the rim is the unit circle).
  touch = [&](cv::Mat& frame) {
    for (int y = 0; y < frame.rows; ++y)
      for (int x = 0; x < frame.cols; ++x) {
        const double dx = x - e.cx, dy = y - e.cy;
        const double u = (dx * std::cos(th) + dy * std::sin(th)) / e.a, v = (-dx * std::sin(th) + dy * std::cos(th)) / e.b;
        const double rho = std::hypot(u, v);
        if (rho > 1.0 && rho < 1.5 && std::abs(std::atan2(v, u)) < M_PI / 6.0) frame.at<std::uint8_t>(y, x) = 130;
      }
  };
  cv::Mat kernel = cv::getGaussianKernel(9, 1.2, CV_64F);
  smear = kernel * kernel.t();
  RimEdgeFit fit;
  const RimFit model = rim(pose, true, &fit);
  touch = nullptr;
  const RimFit clean = rim(pose, true);
  std::printf("clamp beside a sixth of the rim: %d of %zu points left out, %zu further than 0.25 px from the rim; "
              "mean %+.4f px, RMS %.4f px (clean rim: %+.4f px, %.4f px)\n",
              fit.left_out, model.points + static_cast<std::size_t>(fit.left_out), model.off, model.mean_px,
              model.rms_px, clean.mean_px, clean.rms_px);
  // Kept, those crossings are 15 points further than 0.25 px from the rim (RMS 0.15 px);
  // the few left are at the clamp's ends, which the rim's robust fit leaves out (rim_fit.h).
  EXPECT_GE(static_cast<double>(fit.left_out), 0.1 * static_cast<double>(model.points));
  EXPECT_LE(model.off, 5u);
  EXPECT_EQ(clean.off, 0u);
}

// Blur pulls a curved edge's mid-level in by sigma^2 / (2 rho): on a head-on 27 px rim at
// 1.5 px blur about 0.04 px, a rim 0.16 % too small and the distance as much too large.
TEST_F(RimEdgeTest, UndoesTheBlursShrinkOfACurvedEdge) {
  scene.blur_sigma_px = 1.5;
  const Pose pose = makePose(cam, 1500, 0, 0, 10, 300.3, 250.7);
  const RimFit own = rim(pose, false), model = rim(pose, true);
  print("head-on 27 px rim, blur 1.5", own, model);
  EXPECT_LT(own.mean_px, -0.025);
  EXPECT_LT(std::abs(model.mean_px), 0.01);
}

// Noise enters a point through its own two plateaus (scaled by the area window's 9 pixels);
// levels fitted over the whole rim leave only the pixels at the edge.
TEST_F(RimEdgeTest, NoisyRimIsQuieter) {
  scene.blur_sigma_px = 1.0;
  scene.noise_sigma = 4.0;
  const Pose pose = makePose(cam, 900, 30, 60, 10, 300.3, 250.7);
  const RimFit own = rim(pose, false), model = rim(pose, true);
  print("noise 4 at 0.9 m", own, model);
  EXPECT_LT(model.rms_px, 0.7 * own.rms_px);
}

// Light falling off across the target: the levels are planes, so a strong slope moves no
// point off the rim.
TEST_F(RimEdgeTest, LevelsFollowTheLightAcrossTheTarget) {
  scene.blur_sigma_px = 1.0;
  scene.illumination_gradient = 0.8;
  const Pose pose = makePose(cam, 800, 20, 0, 10, 300.3, 250.7);
  const RimFit model = rim(pose, true);
  std::printf("gradient 0.8: mean %+.4f px, RMS %.4f px\n", model.mean_px, model.rms_px);
  EXPECT_LT(std::abs(model.mean_px), 0.01);
  EXPECT_LT(model.rms_px, 0.02);
}

// The blur the model measures is the renderer's, widened by the pixel's own area and the
// two-pixel difference it is read from (together about 0.45 px). Under wide blur it reads
// low (1.5 px as 1.3): the probes 2-3 px out lie on the profile's tails and see less than
// the whole contrast. That moves both levels alike and leaves their mid-level where it was;
// the levels are the card's and the paper's where the edge is sharp.
TEST_F(RimEdgeTest, MeasuresTheBlur) {
  const Pose pose = makePose(cam, 1000, 25, 40, 10, 300.3, 250.7);
  for (double sigma : {0.0, 0.7, 1.0, 1.5}) {
    scene.blur_sigma_px = sigma;
    RimEdgeFit fit;
    rim(pose, true, &fit);
    ASSERT_TRUE(fit.fitted);
    std::printf("blur %.1f: measured %.3f px, %d points moved\n", sigma, fit.blur_sigma_px, fit.moved);
    const double expected = std::hypot(sigma, 0.45);
    EXPECT_GT(fit.blur_sigma_px, 0.8 * expected);
    EXPECT_LT(fit.blur_sigma_px, expected + 0.15);
    EXPECT_NEAR(0.5 * (fit.dark + fit.bright), 0.5 * (scene.black_level + scene.white_level), 1.0);
    if (sigma <= 0.7) {
      EXPECT_NEAR(fit.dark, scene.black_level, 3.0);
      EXPECT_NEAR(fit.bright, scene.white_level, 3.0);
    }
  }
}

// Motion blur spreads one way: a 5 px horizontal smear (variance 2 px^2) of a head-on rim
// widens its left and right edges and carries light round its top and bottom. The model
// measures that as a covariance and keeps the rim round and of its size.
TEST_F(RimEdgeTest, MotionBlurKeepsTheRimRound) {
  scene.blur_sigma_px = 0.6;
  const Pose pose = makePose(cam, 1500, 0, 0, 10, 300.3, 250.7);
  smear = cv::Mat::ones(1, 5, CV_32F) / 5.0f;
  // The own plateaus' points, then the model placing those same points again.
  RimEdgeFit fit;
  const RimFit own = rim(pose, false), model = rim(pose, true, &fit);
  print("5 px smear", own, model);
  std::printf("blur covariance %.3f %.3f %.3f\n", fit.blur_covariance(0, 0), fit.blur_covariance(0, 1),
              fit.blur_covariance(1, 1));
  ASSERT_TRUE(fit.fitted);
  EXPECT_GT(fit.blur_covariance(0, 0), fit.blur_covariance(1, 1) + 1.5);
  EXPECT_LT(std::abs(fit.blur_covariance(0, 1)), 0.2);
  EXPECT_LT(std::abs(model.mean_px), 0.03);
  EXPECT_LT(model.rms_px, 0.7 * own.rms_px);
  EXPECT_LT(std::abs(model.axis_ratio - 1.0), std::abs(own.axis_ratio - 1.0) + 0.0005);
}

// The contour reports the blur along its widest direction, which the pose choice's margin
// follows (reconstruct.h): a 5 px smear's length shows; a sharp rim's spread is the
// pixel's own; without the model nothing is measured.
TEST_F(RimEdgeTest, ReportsTheWidestBlurSpread) {
  const Pose pose = makePose(cam, 1500, 0, 0, 10, 300.3, 250.7);
  auto spread = [&](bool model) {
    rim(pose, model);
    return ws.rim_blur_spread_px;
  };
  scene.blur_sigma_px = 0.3;
  const double sharp = spread(true);
  scene.blur_sigma_px = 0.6;
  smear = cv::Mat::ones(1, 5, CV_32F) / 5.0f;
  const double smeared = spread(true);
  std::printf("widest blur spread: sharp %.3f px, 5 px smear %.3f px\n", sharp, smeared);
  EXPECT_GT(sharp, 0.3);
  EXPECT_LT(sharp, 0.8);
  // The smear's own spread, sqrt(0.6^2 + 5^2 / 12) = 1.56 px, with the pixel's (0.45 px).
  EXPECT_GT(smeared, 1.3);
  EXPECT_LT(smeared, 1.8);
  EXPECT_EQ(spread(false), 0.0);
}

// A sharp edge (below 0.8 px of blur) is placed by the area under its profile, which
// linear interpolation between two pixels cannot match.
TEST_F(RimEdgeTest, SharpEdgeByArea) {
  const Pose pose = makePose(cam, 1000, 35, 40, 10, 300.3, 250.7);
  const RimFit own = rim(pose, false), model = rim(pose, true);
  print("sharp edge", own, model);
  EXPECT_LT(model.rms_px, 0.02);
  EXPECT_LT(std::abs(model.mean_px), 0.005);
}

// Too few crossings, or crossings that do not belong to the points: nothing moves.
TEST_F(RimEdgeTest, LeavesPointsAloneWithoutEnoughCrossings) {
  scene.blur_sigma_px = 1.0;
  const Pose pose = makePose(cam, 1000, 0, 0, 10, 300.3, 250.7);
  rim(pose, false);
  const Ellipse detected = seenRimEllipse(cam, target, pose);
  const std::vector<Eigen::Vector2d> before = points;
  ws.rim_crossings.pop_back();  // one point without its line
  EXPECT_FALSE(modelRimEdge(image, detected, ws, points).fitted);
  EXPECT_EQ(points, before);
  points.resize(5);
  ws.rim_crossings.resize(5);
  EXPECT_FALSE(modelRimEdge(image, detected, ws, points).fitted);
  const cv::Mat flat(image.size(), CV_8UC1, cv::Scalar(128));
  points = before;
  rim(pose, false);
  EXPECT_FALSE(modelRimEdge(flat, detected, ws, points).fitted);  // no rise anywhere: no blur to measure
  EXPECT_EQ(points, before);
}

}  // namespace
}  // namespace imagepro
