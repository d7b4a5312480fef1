// "Any image of a pattern made to this description, printed or rendered by another program,
// must calibrate": images not drawn by the Virtual source's renderer, photographed through a
// known pose and the thesis camera's lens by cv::remap (every camera pixel's ray, undistorted
// by inverting eq. 4.7, is met with the sheet's plane). First the pattern drawn here from its
// settings description alone with OpenCV's primitives (no code of core/calibration/pattern.h),
// then the printable A3 page of core/calibration/pattern_document.h.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "calibration_scenes.h"
#include "sheet_photo.h"
#include "core/calibration/calibrate.h"
#include "core/calibration/pattern_document.h"

namespace imagepro {
namespace {

constexpr double kSheetPxPerMm = 4.0;
constexpr int kSupersampling = 3;  // camera image drawn 3x3 finer, then averaged
constexpr int kShift = 4;          // cv::circle's fractional bits
constexpr unsigned char kWhite = 230, kBlack = 20, kBeyond = 110;

cv::Point fixedPoint(double x_px, double y_px) {
  return {static_cast<int>(std::lround(x_px * (1 << kShift))), static_cast<int>(std::lround(y_px * (1 << kShift)))};
}

// The description of docs/conventions.md, read off the settings: a white sheet of columns x
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

using testing::PhotoConditions;
using testing::SheetFrame;

// The sheet seen by `camera` (with its distortion) at `pose`, blurred and noisy.
cv::Mat photograph(const cv::Mat& sheet, const SheetFrame& frame, const CameraModel& camera, const Pose& pose,
                   unsigned seed) {
  PhotoConditions c;
  c.supersampling = kSupersampling;
  c.beyond = kBeyond;
  c.seed = seed;
  return testing::photograph(sheet, frame, camera, pose, c);
}

TEST(ForeignPattern, AnIndependentlyDrawnPatternCalibrates) {
  Settings settings;  // the pattern, target and camera of the settings' defaults
  CameraModel lens = settings.camera();
  lens.distortion = kThesisCameraDistortion;
  const cv::Mat sheet = drawSheet(settings.pattern, settings.target);
  const SheetFrame frame{0.5 * sheet.cols - 0.5, 0.5 * sheet.rows - 0.5, kSheetPxPerMm};
  std::vector<cv::Mat> images;
  unsigned seed = 1;
  for (const Pose& view : testing::calibrationViews()) images.push_back(photograph(sheet, frame, lens, view, seed++));

  CalibrationResult r;
  ASSERT_EQ(calibrateDistortion(settings, images, r), Status::Ok);
  EXPECT_LE(r.iterations, 5);
  for (const CalibrationImageReport& im : r.images) {
    EXPECT_EQ(im.status, Status::Ok);
    EXPECT_EQ(im.match.ambiguous, 0);
    EXPECT_GT(im.match.matched, 0.9 * im.spots_expected);
  }
  const FieldComparison c = compareDistortionFields(settings.camera(), r.distortion, kThesisCameraDistortion);
  EXPECT_LT(c.rms_px, 0.1);
  std::printf("independently drawn pattern: field error %.4f px RMS, %.4f px max, %d iterations, residual %.4f px\n",
              c.rms_px, c.max_px, r.iterations, r.rms_residual_px);
}

// The printed page (`imagepro-cli pattern --paper A3 --out page.png`: the page's own layout
// and drawing code, not the Virtual source's renderer) photographed the same way from 500 mm,
// within the A3 working distance of docs/calibration.md. It calibrates with the settings'
// default 61 x 49 grid (the spots off the page are missing; the text and scale bar below the
// grid match no spot) and with the grid set to the page's.
TEST(ForeignPattern, ThePrintedPageCalibrates) {
  Settings settings;
  CameraModel lens = settings.camera();
  lens.distortion = kThesisCameraDistortion;
  constexpr double kDpi = 150.0;
  PatternPage page;
  layoutPatternPage(settings.pattern, settings.target, Paper::A3, page);
  const std::vector<std::uint8_t> png = patternPagePng(page, kDpi);
  const cv::Mat sheet = cv::imdecode(png, cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(sheet.empty());
  ASSERT_FALSE(page.circles.empty());
  const double pxPerMm = kDpi / 25.4;
  const PageCircle& disk = page.circles.front();  // drawn first: the target's disk
  ASSERT_FALSE(disk.black);
  ASSERT_EQ(disk.r_mm, settings.target.radius_mm);
  const SheetFrame frame{disk.x_mm * pxPerMm - 0.5, disk.y_mm * pxPerMm - 0.5, pxPerMm};
  std::vector<cv::Mat> images;
  unsigned seed = 11;
  for (const Pose& view : recommendedCalibrationViews(500.0)) images.push_back(photograph(sheet, frame, lens, view, seed++));

  Settings pageGrid = settings;
  pageGrid.pattern.columns = page.grid_columns;
  pageGrid.pattern.rows = page.grid_rows;
  for (const Settings& s : {settings, pageGrid}) {
    CalibrationResult r;
    ASSERT_EQ(calibrateDistortion(s, images, r), Status::Ok) << s.pattern.columns << " x " << s.pattern.rows;
    for (const CalibrationImageReport& im : r.images) {
      EXPECT_EQ(im.status, Status::Ok);
      EXPECT_EQ(im.match.ambiguous, 0);
    }
    const FieldComparison c = compareDistortionFields(s.camera(), r.distortion, kThesisCameraDistortion);
    EXPECT_LT(c.rms_px, 0.1);
    std::printf("printed A3 page at 500 mm, %d x %d grid in the settings: field error %.4f px RMS, %.4f px max, "
                "reach %.2f, %d iterations\n",
                s.pattern.columns, s.pattern.rows, c.rms_px, c.max_px, r.coverage_radius_fraction, r.iterations);
  }
}

}  // namespace
}  // namespace imagepro
