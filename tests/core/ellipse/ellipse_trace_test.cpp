#include "core/ellipse/ellipse_trace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/common/simd_level.h"

#include "scenes.h"

namespace imagepro {
namespace {

using test::sampleEllipse;

TEST(TraceEllipse, FullAndPartialContours) {
  const Ellipse e{320.0, 240.0, 60.0, 30.0, 30.0};
  EllipseFit fit;
  ASSERT_EQ(fitEllipseDirect(sampleEllipse(e, 400), fit), Status::Ok);
  EllipseTrace trace;
  traceEllipse(fit, sampleEllipse(e, 400), 1.0, cv::Size(), trace);
  EXPECT_DOUBLE_EQ(trace.traced, 1.0);
  EXPECT_DOUBLE_EQ(trace.observable, 1.0);
  EXPECT_EQ(trace.inliers, 400u);
  // Half of the contour (by arc length: the ellipse is symmetric) traces about half.
  traceEllipse(fit, sampleEllipse(e, 200, 0.0, 180.0), 1.0, cv::Size(), trace);
  EXPECT_NEAR(trace.traced, 0.5, 0.03);
  // Points 2 px off are not inliers at 1 px.
  traceEllipse(fit, sampleEllipse({e.cx, e.cy, e.a + 2, e.b + 2, e.angle_deg}, 400), 1.0, cv::Size(), trace);
  EXPECT_EQ(trace.inliers, 0u);
  EXPECT_DOUBLE_EQ(trace.traced, 0.0);
  EXPECT_NEAR(trace.mean_sampson_px, 2.0, 0.15);  // first order: a little short
  // An ellipse centred on the left image border: half of it is observable.
  EllipseFit left;
  ASSERT_EQ(fitEllipseDirect(sampleEllipse({0.0, 240.0, 50.0, 50.0, 0.0}, 100), left), Status::Ok);
  traceEllipse(left, sampleEllipse({0.0, 240.0, 50.0, 50.0, 0.0}, 100, -90.0, 90.0), 1.0, cv::Size(640, 480),
               trace);
  EXPECT_NEAR(trace.observable, 0.5, 0.03);
  EXPECT_NEAR(trace.traced, 0.5, 0.03);
}

// The vector lanes (two or four at a time) and the point-by-point loop give the same
// trace, bit for bit, on noisy points with outliers and a point at the centre.
TEST(TraceEllipse, EveryVectorWidthAgrees) {
  const Ellipse e{200.5, 150.25, 80.0, 35.0, -20.0};
  std::vector<Eigen::Vector2d> points = sampleEllipse(e, 517);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.8);
  for (Eigen::Vector2d& p : points) p += Eigen::Vector2d(noise(rng), noise(rng));
  points[100] = Eigen::Vector2d(e.cx, e.cy);
  EllipseFit fit;
  ASSERT_EQ(fitEllipseDirect(sampleEllipse(e, 400), fit), Status::Ok);
  auto traceAt = [&](SimdLevel ceiling, std::span<const Eigen::Vector2d> pts) {
    setSimdCeiling(ceiling);
    EllipseTrace t;
    traceEllipse(fit, pts, 1.0, cv::Size(400, 300), t);
    setSimdCeiling(SimdLevel::Avx2);
    return t;
  };
  for (std::size_t n : {points.size(), std::size_t{3}, std::size_t{6}}) {
    const std::span<const Eigen::Vector2d> pts(points.data(), n);
    const EllipseTrace narrow = traceAt(SimdLevel::Sse2, pts), wide = traceAt(SimdLevel::Avx2, pts);
    EllipseTrace one_by_one;  // the scalar loop alone: one point at a time
    one_by_one.inliers = 0;
    double total = 0.0, traced_any = 0.0;
    for (const Eigen::Vector2d& p : pts) {
      EllipseTrace single;
      traceEllipse(fit, std::span<const Eigen::Vector2d>(&p, 1), 1.0, cv::Size(400, 300), single);
      one_by_one.inliers += single.inliers;
      total += single.mean_sampson_px;
      traced_any += single.traced;
    }
    EXPECT_EQ(narrow.inliers, wide.inliers);
    EXPECT_EQ(narrow.inliers, one_by_one.inliers);
    EXPECT_EQ(narrow.traced, wide.traced);
    EXPECT_EQ(narrow.mean_sampson_px, wide.mean_sampson_px);
    EXPECT_DOUBLE_EQ(narrow.mean_sampson_px * static_cast<double>(n), total);
    EXPECT_GT(narrow.inliers, 0u);
    EXPECT_GT(traced_any, 0.0);
  }
}

}  // namespace
}  // namespace imagepro
