#include "core/common/lens_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace imagepro {
namespace {

// The thesis camera's coefficients times 2.5: 64 px of displacement at a 640x480 image's corners.
constexpr Distortion kExaggerated{2.5 * kThesisCameraDistortion.k1, 2.5 * kThesisCameraDistortion.k2,
                                  2.5 * kThesisCameraDistortion.p1, 2.5 * kThesisCameraDistortion.p2};

TEST(LensModel, DeltaMatchesEquation47) {
  Distortion d{1e-7, 1e-13, 2e-6, 3e-6};
  const Eigen::Vector2d q(200, -100);
  const double r2 = 200.0 * 200 + 100.0 * 100;
  const Eigen::Vector2d delta = distortionDelta(d, q);
  EXPECT_NEAR(delta.x(), 200 * (1e-7 * r2 + 1e-13 * r2 * r2) + 2 * 2e-6 * 200 * -100 + 3e-6 * (r2 + 2 * 200.0 * 200), 1e-12);
  EXPECT_NEAR(delta.y(), -100 * (1e-7 * r2 + 1e-13 * r2 * r2) + 2e-6 * (r2 + 2 * 100.0 * 100) + 2 * 3e-6 * 200 * -100, 1e-12);
  EXPECT_EQ(distortionDelta(d, Eigen::Vector2d::Zero()), Eigen::Vector2d::Zero());
}

TEST(LensModel, JacobianMatchesFiniteDifferences) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-330, 330);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d q(pos(rng), pos(rng));
    const DistortionJacobian fj = distortionWithJacobian(kExaggerated, q);
    EXPECT_EQ(fj.f, distortionDelta(kExaggerated, q));  // one formula for delta
    const double h = 1e-4;
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d dq = Eigen::Vector2d::Zero();
      dq[k] = h;
      const Eigen::Vector2d column =
          (distortionDelta(kExaggerated, q + dq) - distortionDelta(kExaggerated, q - dq)) / (2 * h);
      EXPECT_NEAR(fj.J(0, k), column.x(), 1e-8);
      EXPECT_NEAR(fj.J(1, k), column.y(), 1e-8);
    }
  }
}

TEST(LensModel, NewtonInverseRoundTripsToItsTolerance) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-330, 330);
  for (const double stepPx : {1e-4, 1e-12}) {
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector2d truth(pos(rng), pos(rng));
      const Eigen::Vector2d seen = truth + distortionDelta(kExaggerated, truth);
      Eigen::Vector2d q = seen;  // the distorted point as the start
      ASSERT_TRUE(invertDistortion(kExaggerated, seen, q, 30, stepPx));
      EXPECT_LT((q - truth).norm(), std::max(1e-9, 1e-3 * stepPx));
    }
  }
  // A start that is already the solution is kept as it is.
  const Eigen::Vector2d truth(120.0, -80.0);
  const Eigen::Vector2d seen = truth + distortionDelta(kExaggerated, truth);
  Eigen::Vector2d q = truth;
  EXPECT_TRUE(invertDistortion(kExaggerated, seen, q, 1, 1e-4));
  EXPECT_EQ(q, truth);
}

TEST(LensModel, BeyondTheFoldThereIsNoInverse) {
  // Barrel distortion r -> r (1 + k1 r^2) with k1 = -1e-6 px^-2 folds at r = 577 px, where
  // the distorted radius peaks at 385 px: a point seen 400 px out has no undistorted position.
  const Distortion barrel{-1e-6, 0.0, 0.0, 0.0};
  const Eigen::Vector2d seen(400.0, 0.0);
  Eigen::Vector2d q = seen;
  EXPECT_FALSE(invertDistortion(barrel, seen, q, 30, 1e-4));
  EXPECT_TRUE(std::isfinite(q.x()) && std::isfinite(q.y()));
  // Inside the fold the same model inverts.
  const Eigen::Vector2d inside(300.0, 0.0);
  q = inside;
  ASSERT_TRUE(invertDistortion(barrel, inside, q, 30, 1e-12));
  EXPECT_NEAR(q.x() * (1.0 - 1e-6 * q.x() * q.x()), 300.0, 1e-9);
}

}  // namespace
}  // namespace imagepro
