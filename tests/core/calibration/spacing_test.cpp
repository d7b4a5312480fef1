#include "core/calibration/spacing.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "core/calibration/pattern.h"

namespace imagepro {
namespace {

CameraModel thesisCamera() {
  CameraModel c;
  c.distortion = kThesisCameraDistortion;
  return c;
}

TEST(SpotSpacing, TheDefaultPatternIsUnambiguousForTheThesisCamera) {
  const auto views = recommendedCalibrationViews(800.0);
  const SpacingCheck c = checkSpotSpacing(thesisCamera(), TargetGeometry{}, PatternGeometry{}, views);
  EXPECT_TRUE(c.unambiguous);
  EXPECT_TRUE(c.all_matched);
  EXPECT_LE(c.worst_ratio, kSpacingMargin);
  EXPECT_GT(c.smallest_gap_px, kSpotClearancePx);
  EXPECT_GT(c.spots, 3000);
  std::printf("25 mm: worst ratio %.3f, smallest gap %.2f px, %d spots\n", c.worst_ratio, c.smallest_gap_px, c.spots);
}

TEST(SpotSpacing, MatchingByIdealPositionsAloneNeedsAWiderSpacing) {
  const auto views = recommendedCalibrationViews(800.0);
  const SpacingCheck c = checkSpotSpacing(thesisCamera(), TargetGeometry{}, PatternGeometry{}, views, false);
  EXPECT_FALSE(c.unambiguous);
  EXPECT_GT(c.worst_ratio, kSpacingMargin);
}

TEST(SpotSpacing, MinimumIsTheSmallestSpacingThatPasses) {
  const auto views = recommendedCalibrationViews(800.0);
  const TargetGeometry t;
  const PatternGeometry p;
  for (const bool neighbours : {true, false}) {
    const double s = minimumSpotSpacingMm(thesisCamera(), t, p, views, neighbours);
    ASSERT_GT(s, 0.0);
    EXPECT_TRUE(checkSpotSpacing(thesisCamera(), t, patternWithSpacing(p, s), views, neighbours).unambiguous);
    EXPECT_FALSE(checkSpotSpacing(thesisCamera(), t, patternWithSpacing(p, s - 0.5), views, neighbours).unambiguous);
    std::printf("neighbour prediction %d: minimum spacing %.1f mm\n", neighbours, s);
  }
  // Without distortion nothing is left to predict: only the spots' separation limits it.
  const double none = minimumSpotSpacingMm(CameraModel{}, t, p, views, false);
  EXPECT_LT(none, minimumSpotSpacingMm(thesisCamera(), t, p, views, false));
  EXPECT_GT(checkSpotSpacing(CameraModel{}, t, patternWithSpacing(p, none), views, false).smallest_gap_px,
            kSpotClearancePx);
}

TEST(SpotSpacing, PatternWithSpacingKeepsTheSheet) {
  const PatternGeometry p;  // 1525 x 1225 mm
  const PatternGeometry q = patternWithSpacing(p, 20.0);
  EXPECT_EQ(q.columns, 77);  // ceil(76.25) = 77, odd
  EXPECT_EQ(q.rows, 63);     // ceil(61.25) = 62 -> 63
  EXPECT_EQ(q.spot_radius_mm, p.spot_radius_mm);
  EXPECT_EQ(patternWithSpacing(p, 25.0).columns, 61);
}

}  // namespace
}  // namespace imagepro
