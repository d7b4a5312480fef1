#include "core/ellipse/direct_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "scenes.h"

namespace imagepro {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expectSameEllipse(const Ellipse& got, const Ellipse& want, double tol_px, double tol_deg) {
  EXPECT_NEAR(got.cx, want.cx, tol_px);
  EXPECT_NEAR(got.cy, want.cy, tol_px);
  EXPECT_NEAR(got.a, want.a, tol_px);
  EXPECT_NEAR(got.b, want.b, tol_px);
  EXPECT_NEAR(test::angleDiffDeg(got.angle_deg, want.angle_deg), 0.0, tol_deg);
}

TEST(DirectFit, ExactRecoveryOfAllParameters) {
  for (const Ellipse e : {Ellipse{320.0, 240.0, 100.0, 40.0, 30.0}, Ellipse{12.5, 470.0, 7.0, 3.0, -61.0},
                          Ellipse{600.0, 20.0, 250.0, 200.0, 89.0}, Ellipse{-50.0, 900.0, 30.0, 5.0, 0.0},
                          Ellipse{1e4, -3e3, 2.0, 1.0, 45.0}}) {
    const auto pts = test::sampleEllipse(e, 50);
    EllipseFit fit;
    ASSERT_EQ(fitEllipseDirect(pts, fit), Status::Ok);
    expectSameEllipse(fit.ellipse, e, 1e-7 * e.a, 1e-6);
    EXPECT_LT(fit.relative_error, 1e-12);
    EXPECT_LT(fit.sampson_px, 1e-7 * e.a);
    EXPECT_EQ(fit.points, 50u);
    EXPECT_LT((fit.conic - conicFromEllipse(e)).norm(), 1e-6);
  }
}

TEST(DirectFit, ExactRecoveryFromPartialArcs) {
  // An arc cut by the image border (thesis fig. 2.27) determines the ellipse as well.
  const Ellipse e{100.0, 80.0, 60.0, 25.0, 20.0};
  for (double span : {180.0, 90.0, 45.0}) {
    const auto pts = test::sampleEllipse(e, 30, 10.0, 10.0 + span);
    EllipseFit fit;
    ASSERT_EQ(fitEllipseDirect(pts, fit), Status::Ok) << span;
    expectSameEllipse(fit.ellipse, e, 1e-6 * e.a, 1e-5);
  }
}

TEST(DirectFit, NoisyRecovery) {
  const Ellipse e{320.0, 240.0, 80.0, 40.0, 25.0};
  const double sigma = 0.3;
  const auto pts = test::sampleEllipse(e, 400, 0.0, 360.0, sigma);
  EllipseFit fit;
  ASSERT_EQ(fitEllipseDirect(pts, fit), Status::Ok);
  expectSameEllipse(fit.ellipse, e, 0.1, 0.3);
  // Mean |N(0, sigma)| along the normal: sigma * sqrt(2 / pi).
  EXPECT_NEAR(fit.sampson_px, sigma * std::sqrt(2.0 / kPi), 0.03);
  EXPECT_LT(fit.relative_error, 1e-3);
}

TEST(DirectFit, RelativeErrorIsSimilarityInvariantSampsonScalesWithSize) {
  const Ellipse e{50.0, 60.0, 30.0, 12.0, 10.0};
  auto pts = test::sampleEllipse(e, 200, 0.0, 360.0, 0.2, 3);
  EllipseFit small, large;
  ASSERT_EQ(fitEllipseDirect(pts, small), Status::Ok);
  for (auto& p : pts) p = 10.0 * p + Eigen::Vector2d(-3000.0, 777.0);
  ASSERT_EQ(fitEllipseDirect(pts, large), Status::Ok);
  EXPECT_NEAR(large.relative_error / small.relative_error, 1.0, 1e-6);
  EXPECT_NEAR(large.sampson_px / small.sampson_px, 10.0, 1e-5);
  EXPECT_NEAR(large.ellipse.a, 10.0 * small.ellipse.a, 1e-6 * large.ellipse.a);
}

TEST(DirectFit, SampsonDistanceOfOffsetPoints) {
  const Ellipse e{0.0, 0.0, 50.0, 50.0, 0.0};
  EllipseFit fit;
  ASSERT_EQ(fitEllipseDirect(test::sampleEllipse(e, 60), fit), Status::Ok);
  std::vector<Eigen::Vector2d> outside = test::sampleEllipse({0.0, 0.0, 50.5, 50.5, 0.0}, 60);
  EXPECT_NEAR(meanSampsonDistance(fit, outside), 0.5, 0.005);
  EXPECT_NEAR(sampsonDistance(fit, 49.0, 0.0), -1.0, 0.02);  // inside is negative
  EXPECT_NEAR(sampsonDistance(fit, 0.0, 52.0), 2.0, 0.05);
}

TEST(DirectFit, PixelAndPointOverloadsAgree) {
  std::vector<EdgePixel> pixels;
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 100; ++i) {
    const double s = 2 * kPi * i / 100;
    const auto x = static_cast<std::int16_t>(std::lround(300 + 40 * std::cos(s)));
    const auto y = static_cast<std::int16_t>(std::lround(200 + 25 * std::sin(s)));
    pixels.push_back({x, y, 0, 0});
    points.emplace_back(x, y);
  }
  EllipseFit a, b;
  ASSERT_EQ(fitEllipseDirect(pixels, a), Status::Ok);
  ASSERT_EQ(fitEllipseDirect(points, b), Status::Ok);
  EXPECT_LT((a.conic - b.conic).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(a.sampson_px, b.sampson_px);
  EXPECT_NEAR(a.ellipse.a, 40.0, 0.5);
  EXPECT_NEAR(a.ellipse.b, 25.0, 0.5);
}

TEST(DirectFit, TooFewPoints) {
  EllipseFit fit;
  EXPECT_EQ(fitEllipseDirect(std::vector<Eigen::Vector2d>{}, fit), Status::TooFewPoints);
  EXPECT_EQ(fitEllipseDirect(test::sampleEllipse({0, 0, 10, 5, 0}, 5), fit), Status::TooFewPoints);
  EXPECT_EQ(fitEllipseDirect(test::sampleEllipse({0, 0, 10, 5, 0}, 6), fit), Status::Ok);
}

TEST(DirectFit, DegenerateInputs) {
  EllipseFit fit;
  std::vector<Eigen::Vector2d> line, same, repeated;
  for (int i = 0; i < 20; ++i) line.emplace_back(3.0 + 2.0 * i, 7.0 - 0.5 * i);
  EXPECT_EQ(fitEllipseDirect(line, fit), Status::DegenerateFit);
  same.assign(10, Eigen::Vector2d(4.0, 4.0));
  EXPECT_EQ(fitEllipseDirect(same, fit), Status::DegenerateFit);
  // Eight points but only four distinct: a whole family of conics passes through them.
  const auto four = test::sampleEllipse({0, 0, 10, 5, 0}, 4);
  for (int k = 0; k < 2; ++k) repeated.insert(repeated.end(), four.begin(), four.end());
  EXPECT_EQ(fitEllipseDirect(repeated, fit), Status::DegenerateFit);
}

TEST(DirectFit, HyperbolaAndParabolaAreNotEllipses) {
  EllipseFit fit;
  std::vector<Eigen::Vector2d> hyperbola, parabola, cross;
  for (int i = 0; i < 40; ++i) {
    const double x = 5.0 + i;
    hyperbola.emplace_back(x, 400.0 / x);   // x y = 400
    parabola.emplace_back(x, x * x / 30.0);  // y = x^2 / 30
  }
  for (int i = -10; i <= 10; ++i) {
    cross.emplace_back(i, 0.5 * i);  // two crossing lines: a degenerate hyperbola
    cross.emplace_back(i, -2.0 * i);
  }
  EXPECT_EQ(fitEllipseDirect(hyperbola, fit), Status::NotAnEllipse);
  EXPECT_EQ(fitEllipseDirect(parabola, fit), Status::NotAnEllipse);
  EXPECT_EQ(fitEllipseDirect(cross, fit), Status::NotAnEllipse);
  // Both branches of a hyperbola: still not an ellipse.
  std::vector<Eigen::Vector2d> both = hyperbola;
  for (const auto& p : hyperbola) both.emplace_back(-p.x(), -p.y());
  EXPECT_EQ(fitEllipseDirect(both, fit), Status::NotAnEllipse);
}

TEST(DirectFit, DigitisedArcsStayEllipses) {
  // Short arcs of pixel-rounded ellipses: their best free conic may be a hyperbola, but
  // not clearly better than the ellipse, so they are fitted, not rejected.
  const Ellipse e{300.0, 200.0, 90.0, 50.0, 15.0};
  for (double span : {120.0, 90.0, 60.0}) {
    std::vector<Eigen::Vector2d> pts;
    for (const auto& p : test::sampleEllipse(e, 200, 30.0, 30.0 + span))
      pts.emplace_back(std::round(p.x()), std::round(p.y()));
    EllipseFit fit;
    EXPECT_EQ(fitEllipseDirect(pts, fit), Status::Ok) << span;
  }
}

}  // namespace
}  // namespace imagepro
