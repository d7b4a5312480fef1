#include <gtest/gtest.h>

#include <cmath>

#include "core/ellipse/ellipse.h"

namespace imagepro {
namespace {

TEST(Conic, RoundTrip) {
  for (const Ellipse e : {Ellipse{320, 240, 100, 40, 30}, Ellipse{-5, 7, 3, 1, -89.5}, Ellipse{1000, 2, 60, 59.9, 90},
                          Ellipse{0, 0, 10, 2, 0}}) {
    const Conic c = conicFromEllipse(e);
    EXPECT_NEAR(c.norm(), 1.0, 1e-12);
    Ellipse back;
    ASSERT_TRUE(ellipseFromConic(c, back));
    EXPECT_NEAR(back.cx, e.cx, 1e-7 * e.a);
    EXPECT_NEAR(back.cy, e.cy, 1e-7 * e.a);
    EXPECT_NEAR(back.a, e.a, 1e-7 * e.a);
    EXPECT_NEAR(back.b, e.b, 1e-7 * e.a);
    EXPECT_NEAR(back.angle_deg, e.angle_deg, 1e-6);
    // The same ellipse with the opposite sign is still recognised.
    ASSERT_TRUE(ellipseFromConic(-c, back));
    EXPECT_NEAR(back.a, e.a, 1e-7 * e.a);
  }
}

TEST(Conic, InsideIsNegativeAndMatrixForm) {
  const Ellipse e{50, 60, 20, 10, 25};
  const Conic c = conicFromEllipse(e);
  const Eigen::Matrix3d M = conicMatrix(c);
  EXPECT_TRUE(M.isApprox(M.transpose()));
  const Eigen::Vector3d centre(e.cx, e.cy, 1), outside(e.cx + 30, e.cy, 1);
  EXPECT_LT(centre.dot(M * centre), 0.0);
  EXPECT_GT(outside.dot(M * outside), 0.0);
  // A point on the major axis end lies on the conic.
  const double t = e.angle_deg * M_PI / 180.0;
  const Eigen::Vector3d tip(e.cx + e.a * std::cos(t), e.cy + e.a * std::sin(t), 1);
  EXPECT_NEAR(tip.dot(M * tip), 0.0, 1e-12);
}

TEST(Conic, NonEllipsesRejected) {
  Ellipse out;
  Conic hyperbola;
  hyperbola << 1, 0, -1, 0, 0, -1;  // x^2 - y^2 = 1
  EXPECT_FALSE(ellipseFromConic(hyperbola, out));
  Conic parabola;
  parabola << 1, 0, 0, 0, -1, 0;  // y = x^2
  EXPECT_FALSE(ellipseFromConic(parabola, out));
  Conic imaginary;
  imaginary << 1, 0, 1, 0, 0, 1;  // x^2 + y^2 = -1
  EXPECT_FALSE(ellipseFromConic(imaginary, out));
  Conic point;
  point << 1, 0, 1, 0, 0, 0;
  EXPECT_FALSE(ellipseFromConic(point, out));
  Conic nan = Conic::Constant(std::nan(""));
  EXPECT_FALSE(ellipseFromConic(nan, out));
}

}  // namespace
}  // namespace imagepro
