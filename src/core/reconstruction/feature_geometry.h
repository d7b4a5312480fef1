#pragma once
// Helpers shared by the feature extraction's parts (crop.cpp, contour.cpp, rim_edge.cpp,
// spot_search.cpp): the detected ellipse as a quadratic form, libm-free rounding for their
// hot loops, and a grey row or column read along its length.
// Private to core/reconstruction.
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

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
  double rho2(double x, double y) const { return norm2(x - cx, y - cy); }
  // The squared length of (dx, dy) measured in the ellipse's radii.
  double norm2(double dx, double dy) const { return P * dx * dx + 2.0 * Q * dx * dy + R * dy * dy; }
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

// One image row or column of 8-bit pixels, indexed by its image coordinate k in
// [first, last]: the grey frame's whole line, or the binary crop's part of it.
struct PixelLine {
  const std::uint8_t* data = nullptr;  // the pixel at `first`
  std::ptrdiff_t stride = 1;
  int first = 0, last = -1;

  static PixelLine row(const cv::Mat& m, int y, int x0 = 0) {
    return {m.ptr<std::uint8_t>(y), 1, x0, x0 + m.cols - 1};
  }
  static PixelLine column(const cv::Mat& m, int x, int y0 = 0) {
    return {m.ptr<std::uint8_t>(0) + x, static_cast<std::ptrdiff_t>(m.step[0]), y0, y0 + m.rows - 1};
  }
  bool contains(int k) const { return k >= first && k <= last; }
  double at(int k) const { return data[(k - first) * stride]; }
  bool above(int k, int level) const { return contains(k) && data[(k - first) * stride] > level; }
  bool interp(double x, double& value) const {
    const int k = floorToInt(x);
    if (k < first || k + 1 > last) return false;
    const double f = x - k;
    value = (1.0 - f) * at(k) + f * at(k + 1);
    return true;
  }
};

// The crossing nearest x0 (within 3 px) of a grey line with `level`, the profile
// interpolated linearly between pixels; only a rise towards the inside (`in`, +1 or -1)
// counts.
inline bool levelCrossing(const PixelLine& line, int in, double level, double& x0) {
  constexpr int kSearchPx = 3;
  const int k0 = floorToInt(x0);
  double best = 0.0;
  bool found = false;
  for (int k = std::max(k0 - kSearchPx, line.first); k <= std::min(k0 + kSearchPx, line.last - 1); ++k) {
    const double g0 = line.at(k), g1 = line.at(k + 1);
    if ((g1 - g0) * in <= 0.0 || (g0 - level) * (g1 - level) > 0.0) continue;
    const double x = k + (level - g0) / (g1 - g0);
    if (!found || std::abs(x - x0) < std::abs(best - x0)) best = x;
    found = true;
  }
  if (found) x0 = best;
  return found;
}

}  // namespace imagepro::feature_detail
