#include "core/tracking/polynomial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace imagepro {
namespace {

TEST(Polynomial, ExtrapolatesExactPolynomialsOfEveryDegree) {
  const double coeffs[4] = {3.0, -2.0, 0.5, 0.01};
  for (int degree = 0; degree <= 3; ++degree) {
    std::vector<double> t, x;
    for (int i = 0; i < 10; ++i) {
      const double ti = 0.04 * i + 12.0;  // 25 Hz, far from t = 0
      double xi = 0, p = 1;
      for (int j = 0; j <= degree; ++j, p *= ti) xi += coeffs[j] * p;
      t.push_back(ti);
      x.push_back(xi);
    }
    const double tn = 0.04 * 10 + 12.0;
    double expected = 0, p = 1;
    for (int j = 0; j <= degree; ++j, p *= tn) expected += coeffs[j] * p;
    const Extrapolation e = extrapolatePolynomial(t, x, degree, tn);
    EXPECT_NEAR(e.estimate, expected, 1e-6 * std::max(1.0, std::abs(expected))) << "degree " << degree;
    EXPECT_NEAR(e.r, 1.0, 1e-9);
  }
}

TEST(Polynomial, DegreeIsLimitedByTheNumberOfSamples) {
  const std::vector<double> t{0, 1}, x{1, 3};
  // Degree 3 asked, two samples: a line through both.
  EXPECT_NEAR(extrapolatePolynomial(t, x, 3, 2).estimate, 5.0, 1e-12);
  const std::vector<double> t1{5}, x1{7};
  EXPECT_NEAR(extrapolatePolynomial(t1, x1, 2, 6).estimate, 7.0, 1e-12);
}

TEST(Polynomial, CorrelationMatchesEquation36) {
  // A line fitted to a parabola: r^2 = 1 - SSres/SStot computed by hand.
  const std::vector<double> t{0, 1, 2, 3, 4}, x{0, 1, 4, 9, 16};
  const Extrapolation e = extrapolatePolynomial(t, x, 1, 5);
  // Least-squares line: slope 4, intercept -2; residuals 2,-1,-2,-1,2.
  const double ssres = 4 + 1 + 4 + 1 + 4, mean = 6, sstot = 36 + 25 + 4 + 9 + 100;
  (void)mean;
  EXPECT_NEAR(e.r, std::sqrt((sstot - ssres) / sstot), 1e-12);
  EXPECT_NEAR(e.estimate, 18.0, 1e-12);
}

TEST(Polynomial, ConstantDataHasPerfectCorrelation) {
  const std::vector<double> t{0, 1, 2, 3}, x{4, 4, 4, 4};
  const Extrapolation e = extrapolatePolynomial(t, x, 2, 4);
  EXPECT_DOUBLE_EQ(e.r, 1.0);
  EXPECT_NEAR(e.estimate, 4.0, 1e-12);
}

TEST(Polynomial, NoisyDataNeverGivesNaN) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 1);
  for (int k = 0; k < 200; ++k) {
    std::vector<double> t, x;
    for (int i = 0; i < 10; ++i) {
      t.push_back(i * 0.04);
      x.push_back(noise(rng));
    }
    const Extrapolation e = extrapolatePolynomial(t, x, 3, 0.4);
    EXPECT_TRUE(std::isfinite(e.estimate));
    EXPECT_GE(e.r, 0.0);
    EXPECT_LE(e.r, 1.0);
  }
}

}  // namespace
}  // namespace imagepro
