#include <cmath>

#include "core/ellipse/ellipse.h"

namespace imagepro {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Conic conicFromEllipse(const Ellipse& e) {
  const double t = e.angle_deg * kPi / 180.0;
  const double cs = std::cos(t), sn = std::sin(t);
  const double ia2 = 1.0 / (e.a * e.a), ib2 = 1.0 / (e.b * e.b);
  const double A = cs * cs * ia2 + sn * sn * ib2;
  const double B = 2.0 * cs * sn * (ia2 - ib2);
  const double C = sn * sn * ia2 + cs * cs * ib2;
  Conic c;
  c << A, B, C, -2.0 * A * e.cx - B * e.cy, -B * e.cx - 2.0 * C * e.cy,
      A * e.cx * e.cx + B * e.cx * e.cy + C * e.cy * e.cy - 1.0;
  return c / c.norm();
}

bool ellipseFromConic(const Conic& conic, Ellipse& out) {
  if (!conic.allFinite()) return false;
  // Orient the conic so that its quadratic part is positive definite for an ellipse.
  const Conic c = conic(0) + conic(2) < 0.0 ? Conic(-conic) : conic;
  const double a = c(0), b = c(1), cc = c(2), d = c(3), e = c(4), f = c(5);
  const double disc = 4.0 * a * cc - b * b;  // > 0 for an ellipse (eq. 2.29)
  const double scale = a * a + 0.5 * b * b + cc * cc;
  if (!(disc > 1e-14 * scale)) return false;
  const double x0 = (b * e - 2.0 * cc * d) / disc;
  const double y0 = (b * d - 2.0 * a * e) / disc;
  const double f0 = 0.5 * (d * x0 + e * y0) + f;  // conic value at the centre
  const double mean = 0.5 * (a + cc);
  const double radius = std::hypot(0.5 * (a - cc), 0.5 * b);
  const double lmin = mean - radius, lmax = mean + radius;  // eigenvalues of the quadratic part
  if (!(lmin > 0.0) || !(f0 < 0.0)) return false;  // imaginary ellipse or a single point
  out.cx = x0;
  out.cy = y0;
  out.a = std::sqrt(-f0 / lmin);  // the smaller eigenvalue belongs to the major axis
  out.b = std::sqrt(-f0 / lmax);
  if (radius <= 1e-12 * mean) {
    out.angle_deg = 0.0;  // a circle: no preferred direction
  } else {
    // 0.5*atan2(b, a - c) is the direction of the largest eigenvalue (the minor axis).
    double deg = 0.5 * std::atan2(b, a - cc) * 180.0 / kPi + 90.0;
    while (deg > 90.0) deg -= 180.0;
    while (deg <= -90.0) deg += 180.0;
    out.angle_deg = deg;
  }
  return std::isfinite(out.a) && std::isfinite(out.b) && std::isfinite(out.cx) && std::isfinite(out.cy);
}

Eigen::Matrix3d conicMatrix(const Conic& c) {
  Eigen::Matrix3d m;
  m << c(0), 0.5 * c(1), 0.5 * c(3),  //
      0.5 * c(1), c(2), 0.5 * c(4),   //
      0.5 * c(3), 0.5 * c(4), c(5);
  return m;
}

}  // namespace imagepro
