#include "core/reconstruction/rim_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace imagepro {
namespace {

// Points of the ellipse (cx, cy, a, b, angle) at eccentric angles t from `from` to `to`
// (radians), `n` of them, each moved along its normal by Gaussian noise of `sigma` px.
std::vector<Eigen::Vector2d> arc(const Ellipse& e, double from, double to, int n, double sigma, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, sigma);
  const double th = e.angle_deg * M_PI / 180.0;
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < n; ++k) {
    const double t = from + (to - from) * (k + 0.5) / n;
    const Eigen::Vector2d local(e.a * std::cos(t), e.b * std::sin(t));
    const Eigen::Vector2d normal = Eigen::Vector2d(e.b * std::cos(t), e.a * std::sin(t)).normalized();
    const Eigen::Vector2d q = local + noise(rng) * normal;
    points.emplace_back(e.cx + q.x() * std::cos(th) - q.y() * std::sin(th),
                        e.cy + q.x() * std::sin(th) + q.y() * std::cos(th));
  }
  return points;
}

const Ellipse kRim{412.3, 251.7, 80.0, 55.0, 23.0};

TEST(RimFit, ACleanRimKeepsEveryPointAndIsSeenWhole) {
  std::mt19937 rng(3);
  std::vector<Eigen::Vector2d> ideal = arc(kRim, -M_PI, M_PI, 200, 0.05, rng), seen = ideal;
  RimFitWorkspace ws;
  RimFit rim;
  ASSERT_EQ(fitRim(ideal, seen, true, ws, rim), Status::Ok);
  EXPECT_EQ(rim.kept, 200u);
  EXPECT_EQ(ideal.size(), 200u);
  EXPECT_DOUBLE_EQ(rim.seen, 1.0);
  EXPECT_NEAR(rim.fit.ellipse.cx, kRim.cx, 0.02);
  EXPECT_NEAR(rim.fit.ellipse.a, kRim.a, 0.02);
}

// An occluder's straight edge within the band where the rim was searched: its points pull
// the plain fit by pixels; the robust fit leaves them out and finds the rim again.
TEST(RimFit, AnOccludersEdgeIsLeftOutOfTheRim) {
  std::mt19937 rng(5);
  // Three quarters of the rim seen, the rest hidden behind a strip whose edge lies 1.5-3 px
  // inside the rim.
  std::vector<Eigen::Vector2d> ideal = arc(kRim, -0.75 * M_PI, M_PI, 150, 0.05, rng);
  const std::vector<Eigen::Vector2d> inner = arc({kRim.cx, kRim.cy, kRim.a - 3.0, kRim.b - 1.5, kRim.angle_deg},
                                                 -M_PI, -0.75 * M_PI, 25, 0.05, rng);
  ideal.insert(ideal.end(), inner.begin(), inner.end());
  std::vector<Eigen::Vector2d> seen = ideal;
  for (Eigen::Vector2d& p : seen) p += Eigen::Vector2d(0.5, -0.25);  // as seen: any parallel list

  RimFitWorkspace ws;
  RimFit plain, robust;
  std::vector<Eigen::Vector2d> all = ideal, all_seen = seen;
  ASSERT_EQ(fitRim(all, all_seen, false, ws, plain), Status::Ok);
  EXPECT_EQ(plain.kept, 175u);
  EXPECT_GT(std::hypot(plain.fit.ellipse.cx - kRim.cx, plain.fit.ellipse.cy - kRim.cy) +
                std::abs(plain.fit.ellipse.a - kRim.a),
            0.2);

  ASSERT_EQ(fitRim(ideal, seen, true, ws, robust), Status::Ok);
  EXPECT_EQ(robust.kept, 150u);
  ASSERT_EQ(seen.size(), ideal.size());
  for (std::size_t i = 0; i < ideal.size(); ++i) EXPECT_EQ(seen[i], ideal[i] + Eigen::Vector2d(0.5, -0.25));
  EXPECT_NEAR(robust.fit.ellipse.cx, kRim.cx, 0.05);
  EXPECT_NEAR(robust.fit.ellipse.cy, kRim.cy, 0.05);
  EXPECT_NEAR(robust.fit.ellipse.a, kRim.a, 0.05);
  EXPECT_NEAR(robust.fit.ellipse.b, kRim.b, 0.05);
  EXPECT_NEAR(robust.seen, 0.875, 1.0 / kRimArcs + 1e-9);
}

// A far target's rim, 25 px across its major semi-axis, with a clamp's edge 0.8 px inside
// it over a sixth of the rim: every point lies within 0.6 px of the plain fit, which the
// edge pulls by a tenth of a pixel and more (on a target seen nearly along its axis,
// enough to turn the pose to the rim's other circle). The band's floor (kMinRimBandPx,
// 0.3 px) is tight enough to leave the edge out; a floor of 0.6 px kept it.
TEST(RimFit, AnOccludersEdgeJustInsideAFarRimIsLeftOut) {
  std::mt19937 rng(11);
  const Ellipse far{640.2, 360.9, 25.0, 23.0, -40.0};
  const double kEdgeInsidePx = 0.8;
  std::vector<Eigen::Vector2d> ideal = arc(far, -M_PI / 3.0, 2.0 * M_PI - M_PI / 3.0, 150, 0.05, rng);
  const std::vector<Eigen::Vector2d> edge =
      arc({far.cx, far.cy, far.a - kEdgeInsidePx, far.b - kEdgeInsidePx, far.angle_deg}, -2.0 * M_PI / 3.0, -M_PI / 3.0, 30, 0.05, rng);
  ideal.insert(ideal.end(), edge.begin(), edge.end());
  std::vector<Eigen::Vector2d> seen = ideal;

  RimFitWorkspace ws;
  RimFit plain, robust;
  std::vector<Eigen::Vector2d> all = ideal, all_seen = seen;
  ASSERT_EQ(fitRim(all, all_seen, false, ws, plain), Status::Ok);
  EXPECT_GT(std::abs(plain.fit.ellipse.b - far.b) + std::abs(plain.fit.ellipse.a - far.a), 0.08);

  ASSERT_EQ(fitRim(ideal, seen, true, ws, robust), Status::Ok);
  EXPECT_LE(robust.kept, 155u);
  EXPECT_NEAR(robust.fit.ellipse.a, far.a, 0.03);
  EXPECT_NEAR(robust.fit.ellipse.b, far.b, 0.03);
  EXPECT_NEAR(robust.fit.ellipse.cx, far.cx, 0.03);
  EXPECT_NEAR(robust.fit.ellipse.cy, far.cy, 0.03);
}

TEST(RimFit, TooFewPointsOnTheRimIsTooFewPoints) {
  std::mt19937 rng(7);
  std::vector<Eigen::Vector2d> ideal = arc(kRim, -M_PI, M_PI, 5, 0.0, rng), seen = ideal;
  RimFitWorkspace ws;
  RimFit rim;
  EXPECT_EQ(fitRim(ideal, seen, true, ws, rim), Status::TooFewPoints);
}

TEST(RimFit, TheShareSeenCountsTheArcsHoldingAPoint) {
  std::mt19937 rng(9);
  EXPECT_DOUBLE_EQ(rimShareSeen(kRim, arc(kRim, -M_PI, 0.0, 64, 0.0, rng)), 0.5);
  EXPECT_DOUBLE_EQ(rimShareSeen(kRim, {}), 0.0);
  EXPECT_DOUBLE_EQ(rimShareSeen(Ellipse{}, arc(kRim, -M_PI, 0.0, 64, 0.0, rng)), 0.0);
}

}  // namespace
}  // namespace imagepro
