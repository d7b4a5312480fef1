#include "core/reconstruction/undistort.h"
#include "core/reconstruction/reconstruct.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace imagepro {
namespace {

CameraModel thesisCamera() {
  CameraModel cam;
  cam.distortion = kThesisCameraDistortion;
  return cam;
}

// Strong composite distortion in the spirit of the thesis's fig. 4.9: the thesis camera's
// coefficients times 2.5, 64 px of displacement at the image corners.
CameraModel exaggeratedCamera() {
  CameraModel cam;
  const Distortion& d = kThesisCameraDistortion;
  cam.distortion = {2.5 * d.k1, 2.5 * d.k2, 2.5 * d.p1, 2.5 * d.p2};
  return cam;
}

// undistortPoints corrects two points at a time in vector lanes (SSE2), an odd last one
// alone: each point comes out as undistortTaylor gives it, to the bit, over the whole image
// (and beyond it) for the thesis camera, the exaggerated one and a radial-only one.
TEST(Undistort, PointsInVectorLanesEqualTheTaylorInverseToTheBit) {
  CameraModel radialOnly;
  radialOnly.distortion = {kThesisCameraDistortion.k1, kThesisCameraDistortion.k2, 0.0, 0.0};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  for (const CameraModel& cam : {thesisCamera(), exaggeratedCamera(), radialOnly}) {
    std::vector<Eigen::Vector2d> points;
    for (int v = -40; v <= cam.height + 40; v += 7)
      for (int u = -40; u <= cam.width + 40; u += 5) points.emplace_back(u + jitter(rng), v + jitter(rng));
    points.emplace_back(cam.u0(), cam.v0());
    if (points.size() % 2 == 0) points.emplace_back(0.0, 0.0);  // an odd count: the last one alone
    ASSERT_EQ(points.size() % 2, 1u);
    std::vector<Eigen::Vector2d> corrected = points;
    undistortPoints(cam, false, corrected);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d expected = undistortTaylor(cam, points[i]);
      ASSERT_EQ(corrected[i].x(), expected.x()) << i;
      ASSERT_EQ(corrected[i].y(), expected.y()) << i;
    }
  }
}

TEST(Undistort, NoDistortionIsIdentity) {
  CameraModel cam;
  const Eigen::Vector2d p(12.25, 470.5);
  EXPECT_EQ(undistortTaylor(cam, p), p);
  EXPECT_EQ(undistortExact(cam, p), p);
  std::vector<Eigen::Vector2d> pts{p, {0, 0}};
  undistortPoints(cam, false, pts);
  EXPECT_EQ(pts[0], p);
}

TEST(Undistort, PrincipalPointIsFixed) {
  const CameraModel cam = exaggeratedCamera();
  const Eigen::Vector2d c(cam.u0(), cam.v0());
  EXPECT_LT((undistortTaylor(cam, c) - c).norm(), 1e-12);
  EXPECT_LT((undistortExact(cam, c) - c).norm(), 1e-12);
}

TEST(Undistort, ExactInverseRoundTripsOverTheImage) {
  for (const CameraModel& cam : {thesisCamera(), exaggeratedCamera()}) {
    for (int v = 0; v < cam.height; v += 7) {
      for (int u = 0; u < cam.width; u += 7) {
        const Eigen::Vector2d x(u, v);
        EXPECT_LT((distortPixel(cam, undistortExact(cam, x)) - x).norm(), 1e-9);
        const Eigen::Vector2d y(u, v);  // and the other way round
        EXPECT_LT((undistortExact(cam, distortPixel(cam, y)) - y).norm(), 1e-9);
      }
    }
  }
}

// Pure radial k1 on the u axis: u = w (1 + k1 w^2), a depressed cubic solved by Cardano.
TEST(Undistort, ExactMatchesClosedFormPureRadial) {
  CameraModel cam;
  cam.distortion = {-8.0e-7, 0, 0, 0};
  for (double w = -320; w <= 320; w += 10) {
    const double u = w * (1 + cam.distortion.k1 * w * w);
    // k1 w^3 + w - u = 0  ->  w^3 + p w + q = 0 with p = 1/k1, q = -u/k1 (p < 0: three real roots
    // possible; the physical one is nearest u).
    const double p = 1.0 / cam.distortion.k1, q = -u / cam.distortion.k1;
    const double m = 2.0 * std::sqrt(-p / 3.0);
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      const double root = m * std::cos(std::acos(3.0 * q / (p * m)) / 3.0 - 2.0 * M_PI * k / 3.0);
      if (std::abs(root - u) < std::abs(best - u)) best = root;
    }
    ASSERT_NEAR(best, w, 1e-7);
    const Eigen::Vector2d px(cam.u0() + u, cam.v0());
    EXPECT_NEAR(undistortExact(cam, px).x() - cam.u0(), best, 1e-9);
    EXPECT_NEAR(undistortExact(cam, px).y(), cam.v0(), 1e-12);
  }
}

// Pure tangential p2 on the u axis: u = w + 3 p2 w^2, v unchanged: a quadratic.
TEST(Undistort, ExactAndTaylorAgainstClosedFormPureTangential) {
  CameraModel cam;
  cam.distortion = {0, 0, 0, 2.0e-5};
  const double p2 = cam.distortion.p2;
  for (double w = -320; w <= 320; w += 10) {
    const double u = w + 3 * p2 * w * w;
    const double closed = (-1.0 + std::sqrt(1.0 + 12.0 * p2 * u)) / (6.0 * p2);
    const Eigen::Vector2d px(cam.u0() + u, cam.v0());
    EXPECT_NEAR(undistortExact(cam, px).x() - cam.u0(), closed, 1e-9);
    // On this axis the Taylor inverse is one Newton step from the distorted point, so its
    // error is h''/(2h') e0^2 with e0 = 3 p2 w^2: about 27 p2^3 w^4.
    const double taylorErr = std::abs(undistortTaylor(cam, px).x() - cam.u0() - closed);
    EXPECT_LE(taylorErr, 2.0 * 27.0 * std::pow(p2, 3) * std::pow(w, 4) + 1e-12);
  }
}

// The Taylor inverse is exact to second order in the distortion: halving the distortion
// divides the error by at least 2^3.
TEST(Undistort, TaylorErrorIsThirdOrderInTheDistortion) {
  CameraModel big = exaggeratedCamera();
  CameraModel half = big;
  half.distortion = {big.distortion.k1 / 2, big.distortion.k2 / 2, big.distortion.p1 / 2,
                     big.distortion.p2 / 2};
  const Eigen::Vector2d corner(5, 5);
  const double eBig = (undistortTaylor(big, corner) - undistortExact(big, corner)).norm();
  const double eHalf = (undistortTaylor(half, corner) - undistortExact(half, corner)).norm();
  EXPECT_GT(eBig, 0.0);
  EXPECT_GT(eBig / eHalf, 7.0);
}

// Thesis 4.5: at most one pixel over the image for its camera, at most six for exaggerated
// composite distortion.
TEST(Undistort, TaylorErrorOverTheWholeImageMeetsTheThesisBounds) {
  const UndistortionError thesis = measureTaylorUndistortionError(thesisCamera());
  EXPECT_LT(thesis.max_residual_exact_px, 1e-9);
  EXPECT_LE(thesis.max_px, 1.0);
  EXPECT_GT(thesis.max_px, 0.0);
  const UndistortionError big = measureTaylorUndistortionError(exaggeratedCamera());
  EXPECT_LT(big.max_residual_exact_px, 1e-9);
  EXPECT_LE(big.max_px, 6.0);
  EXPECT_GT(big.max_px, thesis.max_px);
  // Taylor is far better than no correction at all.
  CameraModel cam = exaggeratedCamera();
  const Eigen::Vector2d corner(0, 0);
  EXPECT_LT((undistortTaylor(cam, corner) - undistortExact(cam, corner)).norm(),
            0.25 * (corner - undistortExact(cam, corner)).norm());
}

// The error's profile over the distance from the principal point and the lens's largest
// displacement, against the same quantities computed pixel by pixel on a small image.
TEST(Undistort, TaylorErrorByRadiusAndTheLargestDisplacement) {
  CameraModel cam = exaggeratedCamera();
  cam.width = 64;
  cam.height = 48;
  cam.principal_point_px = {20.0, 30.0};  // off centre: the rings are about it
  cam.distortion = {200.0 * cam.distortion.k1, 0.0, 10.0 * cam.distortion.p1, 0.0};
  const UndistortionError e = measureTaylorUndistortionError(cam);
  std::vector<double> by_radius;
  double largest = 0.0, worst = 0.0;
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector2d x(u, v), truth = undistortExact(cam, x);
      largest = std::max(largest, (truth - x).norm());
      const double err = (undistortTaylor(cam, x) - truth).norm();
      worst = std::max(worst, err);
      const auto ring = static_cast<std::size_t>(std::floor((x - Eigen::Vector2d(20.0, 30.0)).norm()));
      if (ring >= by_radius.size()) by_radius.resize(ring + 1, 0.0);
      by_radius[ring] = std::max(by_radius[ring], err);
    }
  EXPECT_GT(largest, 1.0);
  EXPECT_DOUBLE_EQ(e.largest_displacement_px, largest);
  ASSERT_EQ(e.max_px_by_radius.size(), by_radius.size());
  // The farthest pixel, (63, 0), lies 52.4 px from the principal point.
  EXPECT_EQ(e.max_px_by_radius.size(), 53u);
  for (std::size_t r = 0; r < by_radius.size(); ++r) EXPECT_DOUBLE_EQ(e.max_px_by_radius[r], by_radius[r]) << r;
  EXPECT_DOUBLE_EQ(*std::max_element(e.max_px_by_radius.begin(), e.max_px_by_radius.end()), e.max_px);
  EXPECT_DOUBLE_EQ(e.max_px, worst);
  EXPECT_LT(e.max_px_by_radius[2], e.max_px_by_radius[40]);  // the error grows outwards
}

}  // namespace
}  // namespace imagepro

namespace imagepro {
namespace {

CameraModel webcamCamera() {
  CameraModel cam;
  cam.width = 1280;
  cam.height = 720;
  cam.pixel_size_mm = {0.003, 0.003};
  cam.image_plane_distance_mm = 3.0;
  cam.principal_point_px = {652.4, 371.6};
  cam.distortion = {-7.5e-8, -1.0e-14, 1.2e-6, -8.0e-7};
  return cam;
}

// The border-and-grid estimate of the Taylor inverse's largest error is the whole image's
// (measured pixel by pixel), for the thesis camera and a wide webcam lens alike.
TEST(WideLens, TaylorErrorEstimateIsTheWholeImagesLargest) {
  for (const CameraModel& cam : {thesisCamera(), webcamCamera()}) {
    const double estimate = taylorInverseErrorPx(cam);
    const double whole = measureTaylorUndistortionError(cam).max_px;
    EXPECT_LE(estimate, whole + 1e-12);
    EXPECT_GE(estimate, 0.98 * whole) << cam.width;
    EXPECT_EQ(taylorInverseErrorPx(cam), estimate);  // asked again: the same
  }
  EXPECT_EQ(taylorInverseErrorPx(CameraModel{}), 0.0);
}

// A lens the Taylor inverse errs on by more than kTaylorInverseLimitPx gets the exact inverse
// without being asked, and says so; the thesis camera keeps the thesis's inverse.
TEST(WideLens, TheExactInverseIsUsedWithoutBeingAsked) {
  Settings s;
  s.camera() = webcamCamera();
  ASSERT_GT(taylorInverseErrorPx(s.camera()), kTaylorInverseLimitPx);
  ReconstructionConfig c = reconstructionConfig(s);
  EXPECT_TRUE(c.options.exact_undistortion);
  EXPECT_TRUE(c.exact_for_wide_lens);
  EXPECT_EQ(lensInverse(c), LensInverse::ExactWideLens);
  EXPECT_STREQ(lensInverseName(lensInverse(c)), "exact-wide-lens");

  s.pipeline.reconstruction.exact_undistortion = true;  // asked: not "without being asked"
  c = reconstructionConfig(s);
  EXPECT_FALSE(c.exact_for_wide_lens);
  EXPECT_EQ(lensInverse(c), LensInverse::Exact);

  s.pipeline.reconstruction.exact_undistortion = false;
  s.camera() = thesisCamera();
  c = reconstructionConfig(s);
  EXPECT_EQ(c.options.exact_undistortion, taylorInverseErrorPx(s.camera()) > kTaylorInverseLimitPx);
  EXPECT_EQ(lensInverse(c), c.exact_for_wide_lens ? LensInverse::ExactWideLens : LensInverse::Taylor);

  s.camera().distortion = {};
  EXPECT_EQ(lensInverse(reconstructionConfig(s)), LensInverse::None);
  s.camera() = webcamCamera();
  s.pipeline.reconstruction.distortion_correction = false;
  EXPECT_EQ(lensInverse(reconstructionConfig(s)), LensInverse::None);
}

}  // namespace
}  // namespace imagepro
