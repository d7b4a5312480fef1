// "Any image of a pattern made to this description, printed or rendered by another program,
// must calibrate": the pattern is drawn here from its settings description alone, with
// OpenCV's primitives (no code of core/calibration/pattern.h or of the Virtual source's
// renderer), onto a sheet image at 4 px/mm, and photographed through a known pose and the
// thesis camera's lens by cv::remap: every camera pixel's ray, undistorted by inverting
// eq. 4.7, is intersected with the sheet's plane.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "calibration_scenes.h"
#include "core/calibration/calibrate.h"

namespace imagepro {
namespace {

constexpr double kSheetPxPerMm = 4.0;
constexpr int kSupersampling = 3;  // camera image drawn 3x3 finer, then averaged
constexpr int kShift = 4;          // cv::circle's fractional bits
constexpr unsigned char kWhite = 230, kBlack = 20, kBeyond = 110;

cv::Point fixedPoint(double x_px, double y_px) {
  return {static_cast<int>(std::lround(x_px * (1 << kShift))), static_cast<int>(std::lround(y_px * (1 << kShift)))};
}

// The description of ARCHITECTURE.md, read off the settings: a white sheet of columns x
// rows spacings; the target (white disk of radius R, a black spot of radius r0 at its
// centre and one rf to its +X) on a black square card; grid spots every spacing, centred
// on the target, none that would touch the card. Sheet pixel (0, 0) is the sheet's corner
// at (-width/2, -height/2) mm.
cv::Mat drawSheet(const PatternGeometry& pattern, const TargetGeometry& target) {
  const double width = pattern.columns * pattern.spot_spacing_mm, height = pattern.rows * pattern.spot_spacing_mm;
  cv::Mat sheet(static_cast<int>(std::ceil(height * kSheetPxPerMm)), static_cast<int>(std::ceil(width * kSheetPxPerMm)),
                CV_8UC1, cv::Scalar(kWhite));
  // Pixel centres sit at half-integers of the sheet's millimetre grid.
  auto px = [&](double x_mm, double y_mm) {
    return fixedPoint((x_mm + 0.5 * width) * kSheetPxPerMm - 0.5, (y_mm + 0.5 * height) * kSheetPxPerMm - 0.5);
  };
  auto radius = [](double r_mm) { return static_cast<int>(std::lround(r_mm * kSheetPxPerMm * (1 << kShift))); };
  const double half = 0.5 * pattern.card_size_mm;
  const double r = pattern.spot_radius_mm;
  for (int row = 0; row < pattern.rows; ++row)
    for (int col = 0; col < pattern.columns; ++col) {
      const double x = (col - 0.5 * (pattern.columns - 1)) * pattern.spot_spacing_mm;
      const double y = (row - 0.5 * (pattern.rows - 1)) * pattern.spot_spacing_mm;
      const double gx = std::max(std::abs(x) - half, 0.0), gy = std::max(std::abs(y) - half, 0.0);
      if (gx * gx + gy * gy <= r * r) continue;  // would touch the card
      cv::circle(sheet, px(x, y), radius(r), cv::Scalar(kBlack), cv::FILLED, cv::LINE_AA, kShift);
    }
  cv::fillConvexPoly(sheet, std::vector<cv::Point>{px(-half, -half), px(half, -half), px(half, half), px(-half, half)},
                     cv::Scalar(kBlack), cv::LINE_AA, kShift);
  cv::circle(sheet, px(0, 0), radius(target.radius_mm), cv::Scalar(kWhite), cv::FILLED, cv::LINE_AA, kShift);
  cv::circle(sheet, px(0, 0), radius(target.spot_radius_mm), cv::Scalar(kBlack), cv::FILLED, cv::LINE_AA, kShift);
  cv::circle(sheet, px(target.spot_offset_mm, 0), radius(target.spot_radius_mm), cv::Scalar(kBlack), cv::FILLED,
             cv::LINE_AA, kShift);
  return sheet;
}

// The sheet seen by `camera` (with its distortion) at `pose`, blurred and noisy.
cv::Mat photograph(const cv::Mat& sheet, const CameraModel& camera, const Pose& pose, unsigned seed) {
  const int w = camera.width * kSupersampling, h = camera.height * kSupersampling;
  cv::Mat mapX(h, w, CV_32FC1), mapY(h, w, CV_32FC1);
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose), n = R.col(2);
  const Eigen::Vector2d pp(camera.u0(), camera.v0());
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector2d seen((i + 0.5) / kSupersampling - 0.5, (j + 0.5) / kSupersampling - 0.5);
      // Invert eq. 4.7 (seen = ideal + delta(ideal)) by fixed-point iteration.
      Eigen::Vector2d ideal = seen;
      for (int k = 0; k < 20; ++k) ideal = seen - distortionDelta(camera.distortion, ideal - pp);
      const Eigen::Vector3d ray = backProjectIdeal(camera, ideal);
      const Eigen::Vector3d onPlane = R.transpose() * (n.dot(T) / n.dot(ray) * ray - T);
      mapX.at<float>(j, i) = static_cast<float>((onPlane.x() * kSheetPxPerMm) + 0.5 * sheet.cols - 0.5);
      mapY.at<float>(j, i) = static_cast<float>((onPlane.y() * kSheetPxPerMm) + 0.5 * sheet.rows - 0.5);
    }
  cv::Mat fine, image;
  cv::remap(sheet, fine, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(kBeyond));
  cv::Mat fineF;
  fine.convertTo(fineF, CV_32F);
  cv::resize(fineF, image, cv::Size(camera.width, camera.height), 0, 0, cv::INTER_AREA);
  cv::GaussianBlur(image, image, cv::Size(), 0.7);
  cv::Mat noise(image.size(), CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 2.0);
  cv::Mat out;
  cv::Mat(image + noise).convertTo(out, CV_8U);
  return out;
}

TEST(ForeignPattern, AnIndependentlyDrawnPatternCalibrates) {
  Settings settings;  // the pattern, target and camera of the settings' defaults
  CameraModel lens = settings.camera;
  lens.distortion = kThesisCameraDistortion;
  const cv::Mat sheet = drawSheet(settings.pattern, settings.target);
  std::vector<cv::Mat> images;
  unsigned seed = 1;
  for (const Pose& view : testing::calibrationViews()) images.push_back(photograph(sheet, lens, view, seed++));

  CalibrationResult r;
  ASSERT_EQ(calibrateDistortion(settings, images, r), Status::Ok);
  EXPECT_LE(r.iterations, 5);
  for (const CalibrationImageReport& im : r.images) {
    EXPECT_EQ(im.status, Status::Ok);
    EXPECT_EQ(im.match.ambiguous, 0);
    EXPECT_GT(im.match.matched, 0.9 * im.spots_expected);
  }
  const FieldComparison c = compareDistortionFields(settings.camera, r.distortion, kThesisCameraDistortion);
  EXPECT_LT(c.rms_px, 0.1);
  std::printf("independently drawn pattern: field error %.4f px RMS, %.4f px max, %d iterations, residual %.4f px\n",
              c.rms_px, c.max_px, r.iterations, r.rms_residual_px);
}

}  // namespace
}  // namespace imagepro
