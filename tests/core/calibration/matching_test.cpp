#include "core/calibration/matching.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "calibration_scenes.h"
#include "core/calibration/spots.h"

namespace imagepro {
namespace {

using testing::calibrationViews;

std::vector<PatternSpot> defaultSpots() {
  std::vector<PatternSpot> spots;
  patternSpots(PatternGeometry{}, TargetGeometry{}, spots);
  return spots;
}

// What a perfect spot finder would report: each ideal spot displaced by the lens.
std::vector<ObservedSpot> perfectObservations(const CameraModel& lens, const std::vector<IdealSpot>& ideal) {
  std::vector<ObservedSpot> seen;
  for (const IdealSpot& s : ideal) seen.push_back({distortPixel(lens, s.ideal), static_cast<int>(s.area_px)});
  return seen;
}

TEST(IdealSpots, FrontalProjectionIsTheScaledGrid) {
  const CameraModel cam;
  const PatternGeometry p;
  const auto spots = defaultSpots();
  std::vector<IdealSpot> ideal;
  const Pose frontal{0, 0, 0, 0, 0, 990.0};
  const double k = 800.0 / 990.0;  // px per mm
  projectPatternSpots(cam, p, spots, frontal, ideal);
  ASSERT_FALSE(ideal.empty());
  for (const IdealSpot& s : ideal) {
    const Eigen::Vector2d& mm = spots[s.spot].position_mm;
    EXPECT_LT((s.ideal - Eigen::Vector2d(319.5 + k * mm.x(), 239.5 + k * mm.y())).norm(), 1e-9);
    EXPECT_NEAR(s.area_px, M_PI * std::pow(4.0 * k, 2), 1e-9);
    EXPECT_NEAR(s.spacing_px, 25.0 * k, 1e-9);
  }
  // The image spans 792 x 594 mm: nodes -15..15 by -11..11, without the 5 x 5 on the card.
  EXPECT_EQ(ideal.size(), static_cast<size_t>(31 * 23 - 25));
}

// Tilted, the ideal position is the centroid of the spot's image, not the image of its centre.
TEST(IdealSpots, TiltedPositionIsTheCentroidOfTheSpotsImage) {
  const CameraModel cam;
  PatternGeometry p;
  p.spot_radius_mm = 10.0;  // large, so the two differ clearly
  const auto spots = defaultSpots();
  std::vector<IdealSpot> ideal;
  const Pose tilted{50.0, -30.0, 10.0, 0, 0, 700.0};
  projectPatternSpots(cam, p, spots, tilted, ideal);
  ASSERT_GT(ideal.size(), 100u);
  const Eigen::Matrix3d R = rotationMatrix(tilted);
  double largestShift = 0.0;
  for (size_t k = 0; k < ideal.size(); k += 37) {
    const Eigen::Vector2d c = spots[ideal[k].spot].position_mm;
    // Shoelace centroid and area of the projected circle as a fine polygon.
    const int n = 4000;
    std::vector<Eigen::Vector2d> poly;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      poly.push_back(projectIdeal(cam, R * Eigen::Vector3d(c.x() + 10 * std::cos(a), c.y() + 10 * std::sin(a), 0) +
                                           translation(tilted)));
    }
    double area = 0;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (int i = 0, j = n - 1; i < n; j = i++) {
      const double cross = poly[j].x() * poly[i].y() - poly[i].x() * poly[j].y();
      area += cross;
      centroid += (poly[j] + poly[i]) * cross;
    }
    centroid /= 3.0 * area;
    area = 0.5 * std::abs(area);
    EXPECT_LT((ideal[k].ideal - centroid).norm(), 1e-3);
    EXPECT_NEAR(ideal[k].area_px, area, 1e-3 * area);
    const Eigen::Vector2d centreImage = projectIdeal(cam, R * Eigen::Vector3d(c.x(), c.y(), 0) + translation(tilted));
    largestShift = std::max(largestShift, (centreImage - ideal[k].ideal).norm());
  }
  EXPECT_GT(largestShift, 0.01);
}

struct MatchCase {
  CameraModel cam;  // distortion: the current estimate (zero)
  CameraModel lens;
  PatternGeometry pattern;
  std::vector<IdealSpot> ideal;
  std::vector<ObservedSpot> seen;
};

MatchCase matchCase(const Distortion& lens, const Pose& pose) {
  MatchCase m;
  m.lens.distortion = lens;
  projectPatternSpots(m.cam, m.pattern, defaultSpots(), pose, m.ideal);
  m.seen = perfectObservations(m.lens, m.ideal);
  return m;
}

Distortion scaled(const Distortion& d, double f) { return {f * d.k1, f * d.k2, f * d.p1, f * d.p2}; }

TEST(SpotMatching, FromTheOriginOutwardsEverySpotFindsItsOwn) {
  // Twice the thesis camera's distortion: some 30 px at the corners, three times the
  // spacing of the far side's spots; the estimate is still zero (the first iteration).
  for (const Pose& pose : calibrationViews()) {
    MatchCase m = matchCase(scaled(kThesisCameraDistortion, 2.0), pose);
    MatchWorkspace ws;
    std::vector<SpotMatch> matches;
    MatchStats stats;
    matchSpots(m.cam, m.pattern, m.ideal, m.seen, true, ws, matches, stats);
    EXPECT_EQ(stats.ambiguous, 0);
    EXPECT_EQ(stats.missing, 0);
    ASSERT_EQ(matches.size(), m.ideal.size());
    for (const SpotMatch& s : matches) EXPECT_EQ(s.ideal, s.observed);
  }
}

TEST(SpotMatching, WithoutTheNeighboursDisplacementTheSpacingIsTooSmall) {
  // The thesis's problem: ideal positions alone, against the displacement of the far corners.
  MatchCase m = matchCase(scaled(kThesisCameraDistortion, 2.0), calibrationViews()[2]);
  MatchWorkspace ws;
  std::vector<SpotMatch> matches;
  MatchStats stats;
  matchSpots(m.cam, m.pattern, m.ideal, m.seen, false, ws, matches, stats);
  int wrong = 0;
  for (const SpotMatch& s : matches) wrong += s.ideal != s.observed;
  EXPECT_GT(wrong + stats.ambiguous + stats.missing, 0);
}

TEST(SpotMatching, MissingSpotsAreLeftOutAndTheRestStillMatch) {
  const MatchCase m = matchCase(kThesisCameraDistortion, calibrationViews()[0]);
  // A spot half way out; then also its outer neighbour in its row, so that the spot beyond
  // the two holes is predicted by its other matched neighbours alone.
  const int half = static_cast<int>(m.ideal.size() / 2);
  const Eigen::Vector2d pp(m.cam.u0(), m.cam.v0());
  int outer = -1;
  for (int k = 0; k < static_cast<int>(m.ideal.size()); ++k)
    if (m.ideal[k].row == m.ideal[half].row && std::abs(m.ideal[k].column - m.ideal[half].column) == 1 &&
        (m.ideal[k].ideal - pp).norm() > (m.ideal[half].ideal - pp).norm())
      outer = k;
  ASSERT_GE(outer, 0);
  for (const std::set<int>& removed : {std::set<int>{half}, std::set<int>{half, outer}}) {
    std::map<int, int> seenIndex;  // observed index -> ideal index
    std::vector<ObservedSpot> seen;
    for (int k = 0; k < static_cast<int>(m.seen.size()); ++k)
      if (!removed.count(k)) {
        seenIndex[static_cast<int>(seen.size())] = k;
        seen.push_back(m.seen[k]);
      }
    MatchWorkspace ws;
    std::vector<SpotMatch> matches;
    MatchStats stats;
    matchSpots(m.cam, m.pattern, m.ideal, seen, true, ws, matches, stats);
    EXPECT_EQ(stats.missing, static_cast<int>(removed.size()));
    EXPECT_EQ(stats.ambiguous, 0);
    EXPECT_EQ(matches.size(), m.ideal.size() - removed.size());
    for (const SpotMatch& s : matches) {
      EXPECT_FALSE(removed.count(s.ideal));
      EXPECT_EQ(seenIndex[s.observed], s.ideal);
    }
  }
}

TEST(SpotMatching, ASecondSpotWithinTheGateIsAnAmbiguity) {
  MatchCase m = matchCase(kThesisCameraDistortion, calibrationViews()[3]);
  const int doubled = static_cast<int>(m.ideal.size() / 3);
  ObservedSpot ghost = m.seen[doubled];
  ghost.centre.x() += 0.3 * m.ideal[doubled].spacing_px;
  m.seen.push_back(ghost);
  MatchWorkspace ws;
  std::vector<SpotMatch> matches;
  MatchStats stats;
  matchSpots(m.cam, m.pattern, m.ideal, m.seen, true, ws, matches, stats);
  EXPECT_EQ(stats.ambiguous, 1);
  for (const SpotMatch& s : matches) {
    EXPECT_NE(s.ideal, doubled);
    EXPECT_EQ(s.ideal, s.observed);
  }
}

TEST(SpotMatching, ASpotOfTheWrongSizeIsNoCandidate) {
  MatchCase m = matchCase(Distortion{}, calibrationViews()[1]);
  const int k = 10;
  m.seen[k].area_px = static_cast<int>(5 * m.ideal[k].area_px) + 1;
  MatchWorkspace ws;
  std::vector<SpotMatch> matches;
  MatchStats stats;
  matchSpots(m.cam, m.pattern, m.ideal, m.seen, true, ws, matches, stats);
  EXPECT_EQ(stats.missing, 1);
  EXPECT_EQ(stats.matched, static_cast<int>(m.ideal.size()) - 1);
}

// Step 5 on rendered images: grey, blurred, noisy, distorted. Each spot's centre is found
// within hundredths of a pixel of where the lens puts the centroid of its ideal image.
TEST(SpotFinder, CentresOfRenderedSpots) {
  Settings settings;
  const auto poses = calibrationViews();
  const auto images = testing::renderViews(settings, kThesisCameraDistortion, poses, testing::realisticScene());
  CameraModel lens = settings.camera();
  lens.distortion = kThesisCameraDistortion;
  std::vector<PatternSpot> spots;
  patternSpots(settings.pattern, settings.target, spots);
  SpotFinderWorkspace ws;
  for (size_t v = 0; v < poses.size(); ++v) {
    std::vector<ObservedSpot> seen;
    ASSERT_EQ(findPatternSpots(images[v], settings.pipeline.threshold, ws, seen), Status::Ok);
    std::vector<IdealSpot> ideal;
    projectPatternSpots(settings.camera(), settings.pattern, spots, poses[v], ideal);
    double sum = 0, worst = 0;
    int found = 0, inside = 0;
    for (const IdealSpot& s : ideal) {
      // The outermost ring lies next to the background beyond the sheet: left out by design.
      if (s.column == 0 || s.row == 0 || s.column == settings.pattern.columns - 1 ||
          s.row == settings.pattern.rows - 1)
        continue;
      const Eigen::Vector2d truth = distortPixel(lens, s.ideal);
      const double r = std::sqrt(s.area_px / M_PI) + 4;  // clear of the border, blur included
      if (truth.x() < r || truth.y() < r || truth.x() > 639 - r || truth.y() > 479 - r) continue;
      ++inside;
      double best = 1e9;
      for (const ObservedSpot& o : seen) best = std::min(best, (o.centre - truth).norm());
      if (best > 0.5 * s.spacing_px) continue;
      ++found;
      sum += best * best;
      worst = std::max(worst, best);
    }
    EXPECT_GT(inside, 400);
    EXPECT_EQ(found, inside) << "view " << v;
    EXPECT_LT(std::sqrt(sum / found), 0.05) << "view " << v;
    EXPECT_LT(worst, 0.25) << "view " << v;
  }
}

TEST(SpotFinder, NamedErrors) {
  SpotFinderWorkspace ws;
  std::vector<ObservedSpot> seen;
  EXPECT_EQ(findPatternSpots(cv::Mat(), ThresholdOptions{}, ws, seen), Status::EmptyFrame);
  EXPECT_EQ(findPatternSpots(cv::Mat(10, 10, CV_32F), ThresholdOptions{}, ws, seen), Status::EmptyFrame);
  EXPECT_EQ(findPatternSpots(cv::Mat(48, 64, CV_8UC1, cv::Scalar(200)), ThresholdOptions{}, ws, seen),
            Status::ThresholdUndefined);
  EXPECT_TRUE(seen.empty());
}

}  // namespace
}  // namespace imagepro
