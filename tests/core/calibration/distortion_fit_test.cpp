#include "core/calibration/distortion_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace imagepro {
namespace {

std::vector<DistortionSample> exactSamples(const Distortion& d, const CameraModel& cam) {
  std::vector<DistortionSample> s;
  for (int y = 0; y < cam.height; y += 20)
    for (int x = 0; x < cam.width; x += 20) {
      const Eigen::Vector2d q(x - cam.u0(), y - cam.v0());
      s.push_back({q, distortionDelta(d, q)});
    }
  return s;
}

// Same parameters: the same displacement to 1e-9 px anywhere in the image.
void expectSame(const Distortion& a, const Distortion& b) {
  EXPECT_LT(compareDistortionFields(CameraModel{}, a, b).max_px, 1e-9);
}

TEST(DistortionFit, DesignRowsAreEquation47) {
  const Distortion d = kThesisCameraDistortion;
  const Eigen::Vector2d q(-250.0, 130.0);
  const Eigen::Vector4d x(d.k1, d.k2, d.p1, d.p2);
  EXPECT_LT((distortionDesignRows(q) * x - distortionDelta(d, q)).norm(), 1e-12);
}

TEST(DistortionFit, RecoversNoiseFreeParametersExactly) {
  const CameraModel cam;
  for (const Distortion& d : {kThesisCameraDistortion, Distortion{3e-7, 0, 0, 0}, Distortion{0, 0, -5e-6, 0},
                              Distortion{-1e-6, 4e-12, 2e-5, -3e-5}}) {
    Distortion fit;
    const auto samples = exactSamples(d, cam);
    ASSERT_EQ(fitDistortion(samples, fit), Status::Ok);
    expectSame(fit, d);
    EXPECT_LT(rmsResidualPx(fit, samples), 1e-9);
  }
}

TEST(DistortionFit, TooFewOrDegenerateSamples) {
  Distortion fit;
  const auto all = exactSamples(kThesisCameraDistortion, CameraModel{});
  EXPECT_EQ(fitDistortion(std::span(all).first(3), fit), Status::TooFewMatches);
  // One position seen many times gives two equations for four unknowns.
  std::vector<DistortionSample> same(20, all[7]);
  EXPECT_EQ(fitDistortion(same, fit), Status::DegenerateFit);
  std::vector<DistortionSample> origin(20);  // all at the principal point: no information
  EXPECT_EQ(fitDistortion(origin, fit), Status::DegenerateFit);
  std::vector<DistortionSample> nan = all;
  nan[3].delta.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fitDistortion(nan, fit), Status::DegenerateFit);
}

TEST(DistortionFit, RelativeChangeIsPerParameterWithAFloorForNegligibleOnes) {
  const CameraModel cam;
  const Distortion d = kThesisCameraDistortion;
  EXPECT_EQ(relativeParameterChange(cam, d, d), 0.0);
  EXPECT_NEAR(relativeParameterChange(cam, Distortion{}, d), 1.0, 1e-12);
  Distortion k1 = d;
  k1.k1 *= 1.005;
  EXPECT_NEAR(relativeParameterChange(cam, d, k1), 0.005 / 1.005, 1e-9);
  // p2 = 1e-9 moves a corner by ~1e-4 px: a change of it is measured against 0.1 px.
  Distortion tinyA = d, tinyB = d;
  tinyA.p2 = 1e-9;
  tinyB.p2 = -1e-9;
  const double p2EffectPerUnit = distortionDesignRows(Eigen::Vector2d(320.0, 240.0)).col(3).norm();
  EXPECT_NEAR(relativeParameterChange(cam, tinyA, tinyB), 2e-9 * p2EffectPerUnit / kNegligibleEffectPx, 1e-9);
}

TEST(DistortionFit, FieldComparisonOverTheImage) {
  const CameraModel cam;
  EXPECT_EQ(compareDistortionFields(cam, kThesisCameraDistortion, kThesisCameraDistortion).max_px, 0.0);
  // A pure k1 difference: largest at the farthest pixel centre, |k1| r^3.
  const Distortion k1{1e-7, 0, 0, 0};
  const FieldComparison c = compareDistortionFields(cam, k1, Distortion{});
  const double r = std::hypot(319.5, 239.5);
  EXPECT_NEAR(c.max_px, 1e-7 * r * r * r, 1e-9);
  double sum = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const double r2 = std::pow(x - cam.u0(), 2) + std::pow(y - cam.v0(), 2);
      sum += 1e-14 * r2 * r2 * r2;
    }
  EXPECT_NEAR(c.rms_px, std::sqrt(sum / (640.0 * 480.0)), 1e-9);
}

TEST(DistortionFit, PlausibleLens) {
  const CameraModel cam;
  EXPECT_TRUE(distortionPlausible(cam, Distortion{}));
  EXPECT_TRUE(distortionPlausible(cam, kThesisCameraDistortion));
  EXPECT_FALSE(distortionPlausible(cam, Distortion{-1e-5, 0, 0, 0}));  // folds the image over
  EXPECT_FALSE(distortionPlausible(cam, Distortion{std::numeric_limits<double>::infinity(), 0, 0, 0}));
  EXPECT_FALSE(distortionPlausible(cam, Distortion{0, 0, 1e-3, 0}));  // hundreds of px
}

}  // namespace
}  // namespace imagepro
