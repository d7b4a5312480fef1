#include "core/calibration/calibrate.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calibration_scenes.h"

namespace imagepro {
namespace {

using testing::calibrationViews;

Distortion blend(const Distortion& a, const Distortion& b, double t) {  // a + t (b - a)
  return {a.k1 + t * (b.k1 - a.k1), a.k2 + t * (b.k2 - a.k2), a.p1 + t * (b.p1 - a.p1), a.p2 + t * (b.p2 - a.p2)};
}

// Displacements of the true lens on a grid over the image, seen through a measurement
// whose error is `feedback` times the estimate's error (as the pose of the pattern plane,
// reconstructed with the estimate, would carry it).
DistortionMeasurement syntheticMeasurement(const CameraModel& cam, const Distortion& truth, double feedback,
                                           int* calls = nullptr) {
  return [=](const Distortion& estimate, std::vector<DistortionSample>& samples) {
    if (calls) ++*calls;
    const Distortion seen = blend(truth, estimate, -feedback);  // truth + feedback (truth - estimate)
    for (int y = 10; y < cam.height; y += 40)
      for (int x = 10; x < cam.width; x += 40) {
        const Eigen::Vector2d q(x - cam.u0(), y - cam.v0());
        samples.push_back({q, distortionDelta(seen, q)});
      }
    return Status::Ok;
  };
}

TEST(CalibrationIteration, NoiseFreeMeasurementsAreRecoveredExactly) {
  const CameraModel cam;
  CalibrationResult r;
  std::vector<CalibrationIteration> seen;
  ASSERT_EQ(iterateDistortion(cam, CalibrationOptions{}, Distortion{},
                              syntheticMeasurement(cam, kThesisCameraDistortion, 0.0), r,
                              [&](const CalibrationIteration& it) { seen.push_back(it); }),
            Status::Ok);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 2);  // the first finds it, the second confirms it
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].iteration, 1);
  EXPECT_NEAR(seen[0].relative_change, 1.0, 1e-9);  // from zero
  EXPECT_LT(seen[1].relative_change, 1e-9);
  EXPECT_LT(compareDistortionFields(cam, r.distortion, kThesisCameraDistortion).max_px, 1e-9);
  EXPECT_LT(r.rms_residual_px, 1e-9);
  EXPECT_EQ(r.history.size(), 2u);
}

TEST(CalibrationIteration, ConvergesFromZeroWhenTheMeasurementDependsOnTheEstimate) {
  const CameraModel cam;
  CalibrationResult r;
  ASSERT_EQ(iterateDistortion(cam, CalibrationOptions{}, Distortion{},
                              syntheticMeasurement(cam, kThesisCameraDistortion, 0.2), r),
            Status::Ok);
  // Errors 0.2, 0.04, 0.008, ... of the truth: relative changes 0.24, 0.048, 0.0096.
  EXPECT_EQ(r.iterations, 4);
  ASSERT_EQ(r.history.size(), 4u);
  for (size_t i = 1; i < r.history.size(); ++i)
    EXPECT_LT(r.history[i].relative_change, r.history[i - 1].relative_change);
  EXPECT_LT(r.history.back().relative_change, 0.01);
  EXPECT_LT(compareDistortionFields(cam, r.distortion, kThesisCameraDistortion).max_px,
            0.01 * compareDistortionFields(cam, kThesisCameraDistortion, Distortion{}).max_px);
}

TEST(CalibrationIteration, DivergenceIsNamed) {
  const CameraModel cam;
  CalibrationResult r;
  // Every estimate's error comes back 1.5 times larger: the estimate soon folds the image.
  EXPECT_EQ(iterateDistortion(cam, CalibrationOptions{}, Distortion{},
                              syntheticMeasurement(cam, kThesisCameraDistortion, -1.5), r),
            Status::Diverged);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(r.iterations, CalibrationOptions{}.max_iterations);
  // Slow convergence that the iteration limit cuts short is reported the same way.
  CalibrationOptions few;
  few.max_iterations = 3;
  int calls = 0;
  EXPECT_EQ(iterateDistortion(cam, few, Distortion{}, syntheticMeasurement(cam, kThesisCameraDistortion, 0.9, &calls),
                              r),
            Status::Diverged);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(r.iterations, 3);
}

TEST(CalibrationIteration, AMeasurementErrorEndsIt) {
  const CameraModel cam;
  CalibrationResult r;
  const DistortionMeasurement none = [](const Distortion&, std::vector<DistortionSample>&) {
    return Status::NoTarget;
  };
  EXPECT_EQ(iterateDistortion(cam, CalibrationOptions{}, Distortion{}, none, r), Status::NoTarget);
  EXPECT_EQ(r.iterations, 0);
}

// Step 3 by the renderer's exact poses (the procedure with the target's reconstruction is
// tested in the full-procedure tests below).
PatternLocator truePoses(const std::vector<cv::Mat>& images, const std::array<Pose, 4>& poses) {
  return [&images, poses](const cv::Mat& grey, const CameraModel&, Pose& pose) {
    for (size_t i = 0; i < images.size(); ++i)
      if (grey.data == images[i].data) {
        pose = poses[i];
        return Status::Ok;
      }
    return Status::NoTarget;
  };
}

class CalibrationProcedure : public ::testing::Test {
 protected:
  void SetUp() override {
    images_ = testing::renderViews(settings_, kThesisCameraDistortion, poses_, testing::realisticScene());
  }
  Settings settings_;
  std::array<Pose, 4> poses_ = calibrationViews();
  std::vector<cv::Mat> images_;
};

TEST_F(CalibrationProcedure, FourViewsWithTheirTruePoses) {
  CalibrationResult r;
  int reported = 0;
  ASSERT_EQ(calibrateDistortion(settings_, images_, r, [&](const CalibrationIteration& it) {
              ++reported;
              EXPECT_EQ(it.images_used, 4);
            }, truePoses(images_, poses_)),
            Status::Ok);
  EXPECT_EQ(reported, r.iterations);
  EXPECT_LE(r.iterations, 5);
  const FieldComparison c = compareDistortionFields(settings_.camera(), r.distortion, kThesisCameraDistortion);
  EXPECT_LT(c.rms_px, 0.1);
  EXPECT_LT(r.rms_residual_px, 0.1);
  for (const CalibrationImageReport& im : r.images) {
    EXPECT_EQ(im.status, Status::Ok);
    EXPECT_EQ(im.match.ambiguous, 0);
    EXPECT_GT(im.match.matched, 400);
    EXPECT_EQ(static_cast<int>(im.correspondences.size()), im.match.matched);
  }
}

// The thesis's own step 7 (eq. 4.8 alone, no pose correction): exact when the pattern
// plane's pose is.
TEST_F(CalibrationProcedure, WithoutPoseCorrectionGivenExactPoses) {
  settings_.pipeline.calibration.refine_pose = false;
  CalibrationResult r;
  ASSERT_EQ(calibrateDistortion(settings_, images_, r, {}, truePoses(images_, poses_)), Status::Ok);
  EXPECT_LE(r.iterations, 5);
  EXPECT_LT(compareDistortionFields(settings_.camera(), r.distortion, kThesisCameraDistortion).rms_px, 0.1);
  for (size_t i = 0; i < r.images.size(); ++i) {
    EXPECT_EQ(rotationMatrix(r.images[i].pose), rotationMatrix(poses_[i]));  // never corrected
    EXPECT_EQ(r.images[i].target_pose.tz_mm, poses_[i].tz_mm);
  }
}

// The whole procedure of thesis 4.6 as the issue measures it: the pattern plane from the
// target's detection and reconstruction, starting from zero distortion.
TEST_F(CalibrationProcedure, FourViewsFromTheTargetAlone) {
  CalibrationResult r;
  ASSERT_EQ(calibrateDistortion(settings_, images_, r), Status::Ok);
  EXPECT_TRUE(r.converged);
  EXPECT_LE(r.iterations, 5);
  const FieldComparison c = compareDistortionFields(settings_.camera(), r.distortion, kThesisCameraDistortion);
  EXPECT_LE(c.rms_px, 0.1);
  for (size_t i = 0; i < r.images.size(); ++i) {
    EXPECT_EQ(r.images[i].status, Status::Ok);
    EXPECT_LT(rotationAngleBetweenDeg(rotationMatrix(r.images[i].pose), rotationMatrix(poses_[i])), 0.5);
  }
  std::printf("field rms %.4f px max %.4f px, %d iterations, residual %.4f px\n", c.rms_px, c.max_px, r.iterations,
              r.rms_residual_px);
}

TEST_F(CalibrationProcedure, AViewWithoutItsTargetIsReportedAndSkipped) {
  // The card and its target covered by a white sheet: the pattern is there, the target not.
  CameraModel lens = settings_.camera();
  lens.distortion = kThesisCameraDistortion;
  const double h = 0.5 * settings_.pattern.card_size_mm + 10.0;
  std::vector<cv::Point> cover;
  const Eigen::Matrix3d R = rotationMatrix(poses_[1]);
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(-h, -h), Eigen::Vector2d(h, -h), Eigen::Vector2d(h, h),
                                   Eigen::Vector2d(-h, h)}) {
    const Eigen::Vector2d px =
        distortPixel(lens, projectIdeal(lens, R * Eigen::Vector3d(c.x(), c.y(), 0.0) + translation(poses_[1])));
    cover.emplace_back(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y())));
  }
  cv::fillConvexPoly(images_[1], cover, cv::Scalar(230));
  CalibrationResult r;
  ASSERT_EQ(calibrateDistortion(settings_, images_, r), Status::Ok);
  EXPECT_EQ(r.images[1].status, Status::NoTarget);
  EXPECT_EQ(r.images[1].match.matched, 0);
  EXPECT_EQ(r.history.back().images_used, 3);
  EXPECT_LE(r.iterations, 5);
  EXPECT_LT(compareDistortionFields(settings_.camera(), r.distortion, kThesisCameraDistortion).rms_px, 0.1);
}

TEST_F(CalibrationProcedure, AnImageWithoutTargetIsReportedAndSkipped) {
  CalibrationResult r;
  const PatternLocator exact = truePoses(images_, poses_);
  const PatternLocator blind = [&](const cv::Mat& grey, const CameraModel& cam, Pose& pose) {
    return grey.data == images_[1].data ? Status::NoTarget : exact(grey, cam, pose);
  };
  ASSERT_EQ(calibrateDistortion(settings_, images_, r, {}, blind), Status::Ok);
  EXPECT_EQ(r.images[1].status, Status::NoTarget);
  EXPECT_EQ(r.history.back().images_used, 3);
  EXPECT_LT(compareDistortionFields(settings_.camera(), r.distortion, kThesisCameraDistortion).rms_px, 0.15);

  const PatternLocator none = [](const cv::Mat&, const CameraModel&, Pose&) { return Status::NoTarget; };
  EXPECT_EQ(calibrateDistortion(settings_, images_, r, {}, none), Status::NoTarget);
  for (const CalibrationImageReport& im : r.images) EXPECT_EQ(im.status, Status::NoTarget);
}

TEST_F(CalibrationProcedure, TheTargetWithoutPatternHasTooFewMatches) {
  cv::Mat target;
  CameraModel lens = settings_.camera();
  lens.distortion = kThesisCameraDistortion;
  renderTarget(lens, settings_.target, testing::realisticScene(), poses_[0], target);
  const std::vector<cv::Mat> one{target};
  CalibrationResult r;
  EXPECT_EQ(calibrateDistortion(settings_, one, r, {},
                                [&](const cv::Mat&, const CameraModel&, Pose& pose) {
                                  pose = poses_[0];
                                  return Status::Ok;
                                }),
            Status::TooFewMatches);
  EXPECT_EQ(r.images[0].status, Status::TooFewMatches);
}

TEST_F(CalibrationProcedure, ADoubleExposureIsAMatchAmbiguity) {
  // The pattern seen twice, 14 mm apart along its x axis (the sheet moved during the
  // exposure): every spot has its twin 14 mm on one side and its neighbour's 11 mm on the
  // other, both within half a spacing.
  CameraModel lens = settings_.camera();
  lens.distortion = kThesisCameraDistortion;
  Pose moved = poses_[2];
  const Eigen::Vector3d shift = rotationMatrix(moved) * Eigen::Vector3d(14.0, 0.0, 0.0);
  moved.tx_mm += shift.x();
  moved.ty_mm += shift.y();
  moved.tz_mm += shift.z();
  cv::Mat second;
  renderPattern(lens, settings_.target, settings_.pattern, testing::realisticScene(), moved, second);
  cv::Mat both;
  cv::min(images_[2], second, both);
  const std::vector<cv::Mat> one{both};
  CalibrationResult r;
  EXPECT_EQ(calibrateDistortion(settings_, one, r, {},
                                [&](const cv::Mat&, const CameraModel&, Pose& pose) {
                                  pose = poses_[2];
                                  return Status::Ok;
                                }),
            Status::MatchAmbiguity);
  EXPECT_EQ(r.images[0].status, Status::MatchAmbiguity);
  EXPECT_GT(r.images[0].match.ambiguous, 0);
}

TEST_F(CalibrationProcedure, TheIterationLimitThroughTheWholeProcedureIsDiverged) {
  // One iteration cannot converge: its relative change from zero is 1.
  settings_.pipeline.calibration.max_iterations = 1;
  CalibrationResult r;
  EXPECT_EQ(calibrateDistortion(settings_, images_, r), Status::Diverged);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  ASSERT_EQ(r.history.size(), 1u);
  EXPECT_NEAR(r.history[0].relative_change, 1.0, 1e-9);
  for (const CalibrationImageReport& im : r.images) EXPECT_EQ(im.status, Status::Ok);  // the images were fine
}

TEST(CalibrationCoverage, TheFarthestMatchedSpotOverTheCornerRadius) {
  const CameraModel cam;  // 640 x 480, principal point (319.5, 239.5)
  const Eigen::Vector2d pp(cam.u0(), cam.v0());
  const double corner = Eigen::Vector2d(320.5, 240.5).norm();  // to (640, 480)
  std::vector<CalibrationImageReport> images(2);
  auto at = [&](double du, double dv) {  // a matched spot whose ideal position is pp + (du, dv)
    SpotCorrespondence c;
    c.ideal_px = pp + Eigen::Vector2d(du, dv);
    return c;
  };
  images[0].status = Status::Ok;
  images[0].correspondences.push_back(at(100.0, 0.0));
  images[0].correspondences.push_back(at(-120.0, 160.0));  // 200 px out
  images[1].status = Status::NoTarget;  // not used: its spots do not count
  images[1].correspondences.push_back(at(300.0, 0.0));
  EXPECT_NEAR(coverageRadiusFraction(cam, images), 200.0 / corner, 1e-12);
  images[1].status = Status::Ok;
  EXPECT_NEAR(coverageRadiusFraction(cam, images), 300.0 / corner, 1e-12);
  EXPECT_EQ(coverageRadiusFraction(cam, std::span<const CalibrationImageReport>()), 0.0);
}

// A sheet the size of the A4 page (11 x 7 spacings, as `imagepro-cli pattern --paper A4`
// prints it) seen at the four views: from 800 mm its spots stay in the middle of the
// image, the fit converges with a small residual and a field wrong by a pixel at the
// corners, which must not pass as a calibration; from 400 mm it covers enough.
TEST(CalibrationCoverage, AnA4SheetTooFarAwayIsPoorCoverage) {
  Settings settings;
  settings.pattern.columns = 11;
  settings.pattern.rows = 7;
  for (const double distance : {800.0, 400.0}) {
    std::array<Pose, 4> views = recommendedCalibrationViews(distance);
    const auto images = testing::renderViews(settings, kThesisCameraDistortion, views, testing::realisticScene());
    CalibrationResult r;
    const Status s = calibrateDistortion(settings, images, r);
    const double fieldRms = compareDistortionFields(settings.camera(), r.distortion, kThesisCameraDistortion).rms_px;
    std::printf("A4 sheet at %.0f mm: %s, reach %.3f of the corner radius, field error %.3f px RMS\n", distance,
                std::string(statusName(s)).c_str(), r.coverage_radius_fraction, fieldRms);
    if (distance > 500.0) {
      EXPECT_EQ(s, Status::PoorCoverage);
      EXPECT_TRUE(r.converged);  // the fit itself converged: only the coverage says it is wrong
      EXPECT_LT(r.coverage_radius_fraction, kMinCoverageRadiusFraction);
      EXPECT_GT(fieldRms, 0.1);  // what the check protects against
      for (const CalibrationImageReport& im : r.images) EXPECT_EQ(im.status, Status::Ok);
    } else {
      EXPECT_EQ(s, Status::Ok);
      EXPECT_GE(r.coverage_radius_fraction, kMinCoverageRadiusFraction);
      EXPECT_LT(fieldRms, 0.1);
    }
  }
}

// The A4 sheet from 1200 mm: its spots reach a quarter of the way to the corners, and the
// first fit over them is already no lens (it folds the image's corners).
TEST(CalibrationCoverage, AnA4SheetFarTooFarAwayDiverges) {
  Settings settings;
  settings.pattern.columns = 11;
  settings.pattern.rows = 7;
  const auto images = testing::renderViews(settings, kThesisCameraDistortion, recommendedCalibrationViews(1200.0),
                                           testing::realisticScene());
  CalibrationResult r;
  EXPECT_EQ(calibrateDistortion(settings, images, r), Status::Diverged);
  EXPECT_FALSE(r.converged);
  ASSERT_FALSE(r.history.empty());
  EXPECT_LT(r.iterations, settings.pipeline.calibration.max_iterations);  // not the iteration limit
  EXPECT_FALSE(distortionPlausible(settings.camera(), r.history.back().distortion));
  for (const CalibrationImageReport& im : r.images) EXPECT_EQ(im.status, Status::Ok);
}

TEST_F(CalibrationProcedure, NoImagesAndEmptyImages) {
  CalibrationResult r;
  EXPECT_EQ(calibrateDistortion(settings_, std::span<const cv::Mat>(), r, {}, truePoses(images_, poses_)),
            Status::TooFewMatches);
  const std::vector<cv::Mat> empty{cv::Mat()};
  EXPECT_EQ(calibrateDistortion(settings_, empty, r, {}, truePoses(images_, poses_)), Status::EmptyFrame);
  // An image of another size than the settings' camera is named as such.
  const std::vector<cv::Mat> half{cv::Mat(240, 320, CV_8UC1, cv::Scalar(128))};
  EXPECT_EQ(calibrateDistortion(settings_, half, r, {}, truePoses(images_, poses_)), Status::FrameSizeMismatch);
  EXPECT_EQ(r.images[0].status, Status::FrameSizeMismatch);
}

}  // namespace
}  // namespace imagepro
