#pragma once
// Helpers shared by the feature extraction's parts (crop.cpp, contour.cpp, spot_search.cpp):
// the detected ellipse as a quadratic form and libm-free rounding for their hot loops.
// Private to core/reconstruction.
#include <cmath>

#include "core/ellipse/ellipse.h"

namespace imagepro::feature_detail {

// The detected ellipse as a quadratic form: rho^2 = P dx^2 + 2 Q dx dy + R dy^2 with
// (dx, dy) from its centre; rho = 1 on the ellipse.
struct EllipseForm {
  double cx = 0, cy = 0, P = 0, Q = 0, R = 0;

  EllipseForm(const Ellipse& e, double scale) : cx(e.cx), cy(e.cy) {
    const double t = e.angle_deg * M_PI / 180.0;
    const double c = std::cos(t), s = std::sin(t);
    const double ia2 = 1.0 / (scale * scale * e.a * e.a), ib2 = 1.0 / (scale * scale * e.b * e.b);
    P = c * c * ia2 + s * s * ib2;
    Q = c * s * (ia2 - ib2);
    R = s * s * ia2 + c * c * ib2;
  }
  double rho2(double x, double y) const {
    const double dx = x - cx, dy = y - cy;
    return P * dx * dx + 2.0 * Q * dx * dy + R * dy * dy;
  }
  // Radius of curvature of the level curve through (x, y): |grad|^3 / |t^T H |grad|^2 t|.
  double curvatureRadius(double x, double y) const {
    const double dx = x - cx, dy = y - cy;
    const double gx = P * dx + Q * dy, gy = Q * dx + R * dy;  // half the gradient
    const double tHt = P * gy * gy - 2.0 * Q * gx * gy + R * gx * gx;  // tangent (-gy, gx)
    const double g2 = gx * gx + gy * gy;
    return std::abs(tHt) > 0.0 ? g2 * std::sqrt(g2) / std::abs(tHt) : INFINITY;
  }
  // The ellipse's crossings of row y (false when it misses the row).
  bool rowCrossings(double y, double& xLeft, double& xRight) const {
    const double dy = y - cy;
    const double disc = Q * Q * dy * dy - P * (R * dy * dy - 1.0);
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    xLeft = cx + (-Q * dy - root) / P;
    xRight = cx + (-Q * dy + root) / P;
    return true;
  }
  bool columnCrossings(double x, double& yTop, double& yBottom) const {
    const double dx = x - cx;
    const double disc = Q * Q * dx * dx - R * (P * dx * dx - 1.0);
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    yTop = cy + (-Q * dx - root) / R;
    yBottom = cy + (-Q * dx + root) / R;
    return true;
  }
  // Is the rim at (x, y) closer to vertical (its normal closer to the u axis)?
  bool normalMostlyHorizontal(double x, double y) const {
    const double dx = x - cx, dy = y - cy;
    return std::abs(P * dx + Q * dy) >= std::abs(Q * dx + R * dy);
  }
  // Distance along unit direction (ux, uy) from the centre to the ellipse.
  double rayLength(double ux, double uy) const {
    return 1.0 / std::sqrt(P * ux * ux + 2.0 * Q * ux * uy + R * uy * uy);
  }
};

// floor() and round() to int without a call into libm (hot loops; finite pixel coordinates).
inline int floorToInt(double v) {
  const int i = static_cast<int>(v);
  return i - (v < i ? 1 : 0);
}
inline int ceilToInt(double v) { return -floorToInt(-v); }
inline int roundToInt(double v) { return floorToInt(v + 0.5); }

}  // namespace imagepro::feature_detail
