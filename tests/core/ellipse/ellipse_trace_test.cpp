#include "core/ellipse/ellipse_trace.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace imagepro
