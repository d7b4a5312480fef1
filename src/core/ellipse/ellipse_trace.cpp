#include "core/ellipse/ellipse_trace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
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
// N doubles in one vector (GCC vector extensions: the arithmetic operators work lane by
// lane, with scalars taken as all lanes), and the matching lane masks.
template <int N>
struct Lanes;
template <>
struct Lanes<2> {
  typedef double V __attribute__((vector_size(16)));
  typedef std::int64_t M __attribute__((vector_size(16)));
  typedef int I __attribute__((vector_size(8)));
};
template <>
struct Lanes<4> {
  typedef double V __attribute__((vector_size(32)));
  typedef std::int64_t M __attribute__((vector_size(32)));
  typedef int I __attribute__((vector_size(16)));
};

// tracePoint on N points at once: the same expressions, evaluated lane by lane, so the
// same operations in the same order and bit for bit the same result (fastAtan2's
// branches become selections). False, with nothing done, when a point is the ellipse's
// centre; the caller then takes the points one by one.
template <int N>
[[gnu::always_inline]] inline bool traceLanes(const TraceFrame& k, const ArcTable& table, const double* xs,
                                              const double* ys, double& total, std::size_t& inliers,
                                              unsigned char* traced) {
  using V = typename Lanes<N>::V;
  using M = typename Lanes<N>::M;
  V x, y;
  for (int i = 0; i < N; ++i) {
    x[i] = xs[i];
    y[i] = ys[i];
  }
  const V zero{};
  const M magnitude = M{} + std::numeric_limits<std::int64_t>::max();  // |a| is a & magnitude

  const V u = (x - k.ox) * k.inv_scale, v = (y - k.oy) * k.inv_scale;
  const V f = k.c0 * u * u + k.c1 * u * v + k.c2 * v * v + k.c3 * u + k.c4 * v + k.c5;
  const V gu = 2.0 * k.c0 * u + k.c1 * v + k.c3;
  const V gv = k.c1 * u + 2.0 * k.c2 * v + k.c4;
  const V g2 = gu * gu + gv * gv;
  for (int i = 0; i < N; ++i)
    if (!(g2[i] > 0.0)) return false;
  V root;
  for (int i = 0; i < N; i += 2) {  // SSE2's square root, two lanes at a time
    const __m128d pair = _mm_sqrt_pd(_mm_set_pd(g2[i + 1], g2[i]));
    root[i] = _mm_cvtsd_f64(pair);
    root[i + 1] = _mm_cvtsd_f64(_mm_unpackhi_pd(pair, pair));
  }
  const V ig = 1.0 / root;
  const V d = k.scale * reinterpret_cast<V>(reinterpret_cast<M>(f) & magnitude) * ig;
  for (int i = 0; i < N; ++i) total += d[i];
  const M outlier = d > k.inlier_px;

  const V step = f * ig * ig * k.scale;
  const V dx = x - step * gu - k.cx, dy = y - step * gv - k.cy;
  const V ey = (-dx * k.sn + dy * k.cs) * k.inv_b, ex = (dx * k.cs + dy * k.sn) * k.inv_a;
  const V ax = reinterpret_cast<V>(reinterpret_cast<M>(ex) & magnitude);
  const V ay = reinterpret_cast<V>(reinterpret_cast<M>(ey) & magnitude);
  const V hi = ay > ax ? ay : ax, lo = ay < ax ? ay : ax;  // std::max(ax, ay), std::min(ax, ay)
  V r;
  atanOfRatio<V>(lo / hi, r);
  r = ay > ax ? 0.5 * kPi - r : r;
  r = ex < zero ? kPi - r : r;
  r = ey < zero ? -r : r;
  V t = hi > zero ? r : zero;
  // arcIndex and ArcTable::arcAt lane by lane; their integer clamps become clamps in
  // doubles before the conversion, which select the same integers.
  using I = typename Lanes<N>::I;
  t = t < zero ? t + kTwoPi : t;
  const V at = t * (kArcSamples / kTwoPi);
  V clamped = at > zero ? at : zero;
  clamped = clamped < kArcSamples - 1 ? clamped : zero + (kArcSamples - 1);
  const I sample = __builtin_convertvector(clamped, I);
  V s0, s1;
  for (int i = 0; i < N; ++i) {
    s0[i] = table.s[static_cast<std::size_t>(sample[i])];
    s1[i] = table.s[static_cast<std::size_t>(sample[i]) + 1];
  }
  const V arc = (s0 + (at - __builtin_convertvector(sample, V)) * (s1 - s0)) * k.arcs_per_px;
  const I index = __builtin_convertvector(arc < k.arcs - 1 ? arc : zero + (k.arcs - 1), I);
  for (int i = 0; i < N; ++i) {
    if (outlier[i] != 0) continue;
    ++inliers;
    traced[index[i]] = 1;
  }
  return true;
}

// Points i .. i + N - 1 (traceLanes, or one by one at the ellipse's centre).
template <int N, class Points, class Get>
[[gnu::always_inline]] inline void traceBlock(const TraceFrame& k, const ArcTable& table, const Points& points,
                                              std::size_t i, Get get, double& total, std::size_t& inliers,
                                              unsigned char* traced) {
  double xs[N], ys[N];
  for (int j = 0; j < N; ++j) std::tie(xs[j], ys[j]) = get(points[i + static_cast<std::size_t>(j)]);
  if (traceLanes<N>(k, table, xs, ys, total, inliers, traced)) return;
  for (int j = 0; j < N; ++j) tracePoint(k, table, xs[j], ys[j], total, inliers, traced);
}

// Four points at a time with AVX, where the processor has it (the same operations as
// with SSE2, in wider registers). Returns how many points it took.
template <class Points, class Get>
__attribute__((target("avx"))) std::size_t traceByFour(const TraceFrame& k, const ArcTable& table,
                                                        const Points& points, Get get, double& total,
                                                        std::size_t& inliers, unsigned char* traced) {
  std::size_t i = 0;
  for (; i + 4 <= points.size(); i += 4) traceBlock<4>(k, table, points, i, get, total, inliers, traced);
  return i;
}

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
  if (simdAllows(SimdLevel::Avx)) i = traceByFour(frame, table, points, get, total, inliers, traced.data());
  for (; i + 2 <= points.size(); i += 2) traceBlock<2>(frame, table, points, i, get, total, inliers, traced.data());
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
