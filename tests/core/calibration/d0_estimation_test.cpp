#include "core/calibration/d0_estimation.h"

#include <gtest/gtest.h>

#include <vector>

#include "calibration_scenes.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

// Thin lens: the focal length that images depth z at distance d0.
double focalLength(double d0, double z) { return d0 * z / (d0 + z); }

// Virtual frames rendered with d0 = 12 mm at known distances: the estimator, given the thin
// lens's focal length, finds 12 mm whatever d0 the settings' camera has, and the depth
// that goes with it is the known distance.
TEST(D0Estimation, RecoversTheKnownD0OfVirtualFramesAtKnownDistances) {
  Settings rendering;
  rendering.camera().image_plane_distance_mm = 12.0;
  Settings settings;  // d0 8 mm: not used
  for (const double distance : {700.0, 1000.0, 1300.0}) {
    Frame frame;
    renderTarget(rendering.camera(), rendering.target, rendering.virtual_scene, Pose{20, -15, 30, 40, -20, distance},
                 frame.image);
    D0Estimator estimator(settings, D0Options{focalLength(12.0, distance), 1e-6, 20});
    FrameResult result;
    D0FrameEstimate out;
    estimator.process(frame, result, out);
    ASSERT_EQ(out.status, Status::Ok) << statusName(out.status);
    EXPECT_NEAR(out.estimate.d0_mm, 12.0, 2e-3) << distance;
    EXPECT_NEAR(out.estimate.depth_mm, distance, 2e-3 * distance);
    EXPECT_LE(out.estimate.iterations, 5);
    ASSERT_EQ(out.estimate.history_mm.size(), static_cast<size_t>(out.estimate.iterations) + 1);
    EXPECT_EQ(out.estimate.history_mm.front(), focalLength(12.0, distance));
  }
}

TEST(D0Estimation, FramesWithoutAnEstimateSayWhy) {
  Settings settings;
  Frame blank;
  blank.image = cv::Mat(settings.camera().height, settings.camera().width, CV_8UC1, cv::Scalar(30));
  D0Estimator estimator(settings, D0Options{7.9, 1e-6, 20});
  FrameResult result;
  D0FrameEstimate out;
  estimator.process(blank, result, out);
  EXPECT_FALSE(ok(out.status));
  Frame target;
  renderTarget(settings.camera(), settings.target, settings.virtual_scene, Pose{0, 0, 0, 0, 0, 800}, target.image);
  D0Estimator no_lens(settings, D0Options{0.0, 1e-6, 20});
  no_lens.process(target, result, out);
  EXPECT_EQ(out.status, Status::InvalidSettings);
  D0Estimator hurried(settings, D0Options{7.9, 1e-12, 1});  // one step cannot reach 1e-12 mm
  hurried.process(target, result, out);
  EXPECT_EQ(out.status, Status::Diverged);
}

TEST(D0Estimation, SummaryIsTheMeanAndSampleDeviation) {
  EXPECT_EQ(summarizeD0({}).count, 0);
  const std::vector<double> one{8.0};
  EXPECT_EQ(summarizeD0(one).sd_mm, 0.0);
  const std::vector<double> three{7.0, 8.0, 9.0};
  const D0Summary s = summarizeD0(three);
  EXPECT_EQ(s.count, 3);
  EXPECT_DOUBLE_EQ(s.mean_mm, 8.0);
  EXPECT_DOUBLE_EQ(s.sd_mm, 1.0);
}

}  // namespace
}  // namespace imagepro
