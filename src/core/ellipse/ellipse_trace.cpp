#include "core/ellipse/ellipse_trace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <tuple>
#include <utility>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "core/common/simd_level.h"
#include "core/ellipse/fast_atan2.h"

namespace imagepro {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;
constexpr double kPi = 0.5 * kTwoPi;
constexpr int kArcSamples = 128;  // parametric samples of the arc-length table
constexpr int kMaxArcs = 512;
constexpr double kArcLengthPx = 3.0;

// cos t and sin t at t = 2 pi k / kArcSamples by a rotation recurrence (no
// trigonometry), the same for every ellipse: computed once.
struct UnitCircle {
  std::array<double, kArcSamples + 1> c{}, s{};
};
const UnitCircle& unitCircle() {
  static const UnitCircle circle = [] {
    UnitCircle u;
    const double step_c = std::cos(kTwoPi / kArcSamples), step_s = std::sin(kTwoPi / kArcSamples);
    double c = 1.0, sn = 0.0;
    u.c[0] = 1.0;
    for (int k = 1; k <= kArcSamples; ++k) {
      const double c2 = c * step_c - sn * step_s;
      sn = sn * step_c + c * step_s;
      c = c2;
      u.c[k] = c;
      u.s[k] = sn;
    }
    return u;
  }();
  return circle;
}

// Points of the ellipse (a cos t, b sin t) and the arc length from t = 0, tabulated at
// t = 2 pi k / kArcSamples.
struct ArcTable {
  std::array<double, kArcSamples + 1> s{}, x{}, y{};
  double perimeter = 0.0;

  ArcTable(double a, double b) {
    const UnitCircle& unit = unitCircle();
    x[0] = a;
    y[0] = 0.0;
    for (int k = 1; k <= kArcSamples; ++k) {
      x[k] = a * unit.c[k];
      y[k] = b * unit.s[k];
    }
    // The chords' lengths, two at a time where SSE2 allows, then their running sum.
    std::array<double, kArcSamples + 1> chord;
    int k = 1;
#if defined(__SSE2__)
    for (; k + 1 <= kArcSamples; k += 2) {
      const __m128d dx = _mm_sub_pd(_mm_loadu_pd(&x[k]), _mm_loadu_pd(&x[k - 1]));
      const __m128d dy = _mm_sub_pd(_mm_loadu_pd(&y[k]), _mm_loadu_pd(&y[k - 1]));
      _mm_storeu_pd(&chord[k], _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy))));
    }
#endif
    for (; k <= kArcSamples; ++k) {
      const double dx = x[k] - x[k - 1], dy = y[k] - y[k - 1];
      chord[k] = std::sqrt(dx * dx + dy * dy);
    }
    for (k = 1; k <= kArcSamples; ++k) s[k] = s[k - 1] + chord[k];
    perimeter = s[kArcSamples];
  }
  double arcAt(double t) const {  // t in [0, 2 pi)
    const double f = t * (kArcSamples / kTwoPi);
    const int k = std::clamp(static_cast<int>(f), 0, kArcSamples - 1);
    return s[k] + (f - k) * (s[k + 1] - s[k]);
  }
};

// What trace() needs per point, fixed for one ellipse.
struct TraceFrame {
  double c0, c1, c2, c3, c4, c5;  // the conic in the fit's normalised frame
  double scale, inv_scale, ox, oy;
  double cx, cy, cs, sn, inv_a, inv_b, b;  // the ellipse
  double inlier_px, arcs_per_px;
  int arcs;
};

// The arc (index) of an inlier's foot at parametric angle t (fastAtan2's range).
inline int arcIndex(const TraceFrame& k, const ArcTable& table, double t) {
  if (t < 0.0) t += kTwoPi;
  return std::min(k.arcs - 1, static_cast<int>(table.arcAt(t) * k.arcs_per_px));
}

// One point: adds its Sampson distance to `total` and, for an inlier, marks its arc.
inline void tracePoint(const TraceFrame& k, const ArcTable& table, double x, double y, double& total,
                       std::size_t& inliers, unsigned char* traced) {
  const double u = (x - k.ox) * k.inv_scale, v = (y - k.oy) * k.inv_scale;
  const double f = k.c0 * u * u + k.c1 * u * v + k.c2 * v * v + k.c3 * u + k.c4 * v + k.c5;
  const double gu = 2.0 * k.c0 * u + k.c1 * v + k.c3;
  const double gv = k.c1 * u + 2.0 * k.c2 * v + k.c4;
  const double g2 = gu * gu + gv * gv;
  if (!(g2 > 0.0)) {  // the centre: as far as the minor semi-axis
    total += k.b;
    return;
  }
  const double ig = 1.0 / std::sqrt(g2);
  const double d = k.scale * std::abs(f) * ig;
  total += d;
  if (d > k.inlier_px) return;
  ++inliers;
  // The arc of the point's foot on the ellipse (one first-order projection step): the
  // raw parametric angle of an off-curve point is far off near the ends of a thin ellipse.
  const double step = f * ig * ig * k.scale;
  const double dx = x - step * gu - k.cx, dy = y - step * gv - k.cy;
  traced[arcIndex(k, table, fastAtan2((-dx * k.sn + dy * k.cs) * k.inv_b, (dx * k.cs + dy * k.sn) * k.inv_a))] = 1;
}

#if defined(__SSE2__)
// The lanes of the trace, once per vector width (see simd_level.h): Ops gives the
// vector of kLanes doubles (GCC vector extensions: the arithmetic operators work lane by
// lane, scalars taken as all lanes), its lane masks and integer lanes, and a square root.
namespace sse2 {
struct Ops {
  static constexpr int kLanes = 2;
  typedef double V __attribute__((vector_size(16)));
  typedef std::int64_t M __attribute__((vector_size(16)));
  typedef int I __attribute__((vector_size(8)));
  static V sqrt(V v) { return reinterpret_cast<V>(_mm_sqrt_pd(reinterpret_cast<__m128d>(v))); }
};
#include "core/ellipse/trace_pass.inc"
}  // namespace sse2

IMAGEPRO_AVX2_BEGIN
namespace avx2 {
struct Ops {
  static constexpr int kLanes = 4;
  typedef double V __attribute__((vector_size(32)));
  typedef std::int64_t M __attribute__((vector_size(32)));
  typedef int I __attribute__((vector_size(16)));
  static V sqrt(V v) { return reinterpret_cast<V>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(v))); }
};
#include "core/ellipse/trace_pass.inc"
}  // namespace avx2
IMAGEPRO_AVX2_END
#endif

template <class Points, class Get>
void trace(const EllipseFit& fit, const Points& points, double inlier_px, cv::Size image,
           EllipseTrace& out, Get get) {
  out = EllipseTrace{};
  const Ellipse& e = fit.ellipse;
  if (!(e.a > 0.0) || !(e.b > 0.0)) return;
  const ArcTable table(e.a, e.b);
  const int arcs = std::clamp(static_cast<int>(std::ceil(table.perimeter / kArcLengthPx)), 8, kMaxArcs);
  const double arcs_per_px = arcs / table.perimeter;
  std::array<unsigned char, kMaxArcs> traced{};
  const double th = e.angle_deg * kPi / 180.0;
  const double cs = std::cos(th), sn = std::sin(th);
  const Conic& c = fit.normalised;
  const TraceFrame frame{.c0 = c(0), .c1 = c(1), .c2 = c(2), .c3 = c(3), .c4 = c(4), .c5 = c(5),
                         .scale = fit.scale, .inv_scale = 1.0 / fit.scale, .ox = fit.origin.x(), .oy = fit.origin.y(),
                         .cx = e.cx, .cy = e.cy, .cs = cs, .sn = sn, .inv_a = 1.0 / e.a, .inv_b = 1.0 / e.b, .b = e.b,
                         .inlier_px = inlier_px, .arcs_per_px = arcs_per_px, .arcs = arcs};
  double total = 0.0;
  std::size_t inliers = 0;
  std::size_t i = 0;
#if defined(__SSE2__)
  if (simdAllows(SimdLevel::Avx2)) i = avx2::tracePoints(frame, table, points, i, get, total, inliers, traced.data());
  i = sse2::tracePoints(frame, table, points, i, get, total, inliers, traced.data());
#endif
  for (; i < points.size(); ++i) {
    const auto [x, y] = get(points[i]);
    tracePoint(frame, table, x, y, total, inliers, traced.data());
  }
  out.inliers = inliers;
  out.mean_sampson_px = points.empty() ? 0.0 : total / static_cast<double>(points.size());
  int n_traced = 0;
  for (int k = 0; k < arcs; ++k) n_traced += traced[k];
  out.traced = static_cast<double>(n_traced) / arcs;
  // Observable: the middle of each arc inside the image (all of them when the ellipse's
  // bounding box is).
  const double half_w = std::sqrt(e.a * e.a * cs * cs + e.b * e.b * sn * sn);
  const double half_h = std::sqrt(e.a * e.a * sn * sn + e.b * e.b * cs * cs);
  const double lo = -0.5, hi_x = image.width - 0.5, hi_y = image.height - 0.5;
  if (image.empty() || (e.cx - half_w >= lo && e.cy - half_h >= lo && e.cx + half_w <= hi_x && e.cy + half_h <= hi_y)) {
    out.observable = 1.0;
    return;
  }
  int n_observable = 0, j = 0;
  for (int k = 0; k < arcs; ++k) {
    const double arc = (k + 0.5) / arcs_per_px;
    while (j < kArcSamples - 1 && table.s[j + 1] < arc) ++j;
    const double span = table.s[j + 1] - table.s[j];
    const double f = span > 0.0 ? (arc - table.s[j]) / span : 0.0;
    const double ex = table.x[j] + f * (table.x[j + 1] - table.x[j]);
    const double ey = table.y[j] + f * (table.y[j + 1] - table.y[j]);
    const double px = e.cx + ex * cs - ey * sn, py = e.cy + ex * sn + ey * cs;
    n_observable += px >= lo && py >= lo && px <= hi_x && py <= hi_y;
  }
  out.observable = static_cast<double>(n_observable) / arcs;
}

}  // namespace

void traceEllipse(const EllipseFit& fit, std::span<const EdgePixel> points, double inlier_px,
                  cv::Size image, EllipseTrace& out) {
  trace(fit, points, inlier_px, image, out,
        [](const EdgePixel& p) { return std::pair<double, double>{p.x, p.y}; });
}

void traceEllipse(const EllipseFit& fit, std::span<const Eigen::Vector2d> points, double inlier_px,
                  cv::Size image, EllipseTrace& out) {
  trace(fit, points, inlier_px, image, out,
        [](const Eigen::Vector2d& p) { return std::pair<double, double>{p.x(), p.y()}; });
}

}  // namespace imagepro
