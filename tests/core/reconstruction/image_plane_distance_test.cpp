#include "core/reconstruction/image_plane_distance.h"

#include <gtest/gtest.h>

#include "core/reconstruction/reconstruct.h"
#include "core/source/virtual_renderer.h"
#include "status_print.h"
#include "test_scenes.h"

namespace imagepro {
namespace {

// Thin lens: the focal length that images depth z at distance d0.
double focalLength(double d0, double z) { return d0 * z / (d0 + z); }

TEST(ImagePlaneDistance, ConvergesOnADepthProportionalToD0) {
  const double d0 = 8.0, z = 900.0, f = focalLength(d0, z);
  ImagePlaneDistanceEstimate est;
  auto depth = [&](double d, double& out) {
    out = z * d / d0;
    return Status::Ok;
  };
  ASSERT_EQ(estimateImagePlaneDistance(f, depth, 1e-9, 20, est), Status::Ok);
  EXPECT_NEAR(est.d0_mm, d0, 1e-8);
  EXPECT_NEAR(est.depth_mm, z, 1e-6);
  EXPECT_LE(est.iterations, 6);
  // The history starts at f and ends at the estimate, each step closer to d0 than the last.
  ASSERT_EQ(est.history_mm.size(), static_cast<size_t>(est.iterations) + 1);
  EXPECT_EQ(est.history_mm.front(), f);
  EXPECT_EQ(est.history_mm.back(), est.d0_mm);
  for (size_t i = 1; i < est.history_mm.size(); ++i)
    EXPECT_LE(std::abs(est.history_mm[i] - d0), std::abs(est.history_mm[i - 1] - d0)) << i;
}

TEST(ImagePlaneDistance, NamedErrors) {
  ImagePlaneDistanceEstimate est;
  auto fine = [](double d, double& out) {
    out = 100 * d;
    return Status::Ok;
  };
  EXPECT_EQ(estimateImagePlaneDistance(0.0, fine, 1e-6, 10, est), Status::InvalidSettings);
  EXPECT_EQ(estimateImagePlaneDistance(8.0, fine, 0.0, 10, est), Status::InvalidSettings);
  EXPECT_EQ(estimateImagePlaneDistance(8.0, fine, 1e-6, 0, est), Status::InvalidSettings);
  auto tooNear = [](double, double& out) {
    out = 5.0;  // inside the focal length: no real image
    return Status::Ok;
  };
  EXPECT_EQ(estimateImagePlaneDistance(8.0, tooNear, 1e-6, 10, est), Status::Diverged);
  auto noTarget = [](double, double&) { return Status::NoTarget; };
  EXPECT_EQ(estimateImagePlaneDistance(8.0, noTarget, 1e-6, 10, est), Status::NoTarget);
  int calls = 0;
  auto wobbling = [&](double, double& out) {
    out = ++calls % 2 ? 800.0 : 1200.0;
    return Status::Ok;
  };
  EXPECT_EQ(estimateImagePlaneDistance(8.0, wobbling, 1e-6, 10, est), Status::Diverged);
}

// Virtual frames rendered with a known d0: reconstructing with the d0 of each step of
// eq. 4.1 from the thin-lens focal length leads back to it.
TEST(ImagePlaneDistance, RecoversTheKnownD0OfVirtualFrames) {
  Settings settings;
  settings.pipeline.reconstruction.contour_mode = ContourMode::SubPixel;
  for (double d0 : {6.0, 8.0, 12.5}) {
    settings.camera().image_plane_distance_mm = d0;
    for (const Pose& truth : {testing::makePose(settings.camera(), 600, 30, 20, 10, 300, 250),
                              testing::makePose(settings.camera(), 1100, 10, -50, 100, 350, 220)}) {
      cv::Mat image;
      renderTarget(settings.camera(), settings.target, settings.virtual_scene, truth, image);
      const Ellipse detected = testing::seenRimEllipse(settings.camera(), settings.target, truth);
      ReconstructionConfig config = reconstructionConfig(settings);
      ReconstructionWorkspace ws;
      ReconstructionResult result;
      auto depthAt = [&](double d, double& depth) {
        config.camera.image_plane_distance_mm = d;
        const Status s = reconstructTarget(config, image, detected, -1, ws, result);
        depth = result.pose.tz_mm;
        return s;
      };
      ImagePlaneDistanceEstimate est;
      ASSERT_EQ(estimateImagePlaneDistance(focalLength(d0, truth.tz_mm), depthAt, 1e-6, 20, est), Status::Ok);
      EXPECT_NEAR(est.d0_mm, d0, 2e-4 * d0) << d0 << " " << truth.tz_mm;
      EXPECT_NEAR(est.depth_mm, truth.tz_mm, 5e-4 * truth.tz_mm);
      EXPECT_LE(est.iterations, 5);
    }
  }
}

}  // namespace
}  // namespace imagepro
