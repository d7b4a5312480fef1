#include "core/ellipse/bennett.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/common/simd_level.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace imagepro {

namespace {

constexpr int kMargin = 2;  // accumulator cells around the path's bounding box
constexpr int kSnap = 2;    // cells
// The coarse screen (bennettAccumulate): paths of at least kMinScreenPoints sampled
// pixels whose coarse peak share is below kScreenShare of the required one stop there.
constexpr std::size_t kMinScreenPoints = 48;
constexpr double kScreenShare = 0.5;
// A ring is point-symmetric about the peak while sum|A(q) - A(q')| / sum(A(q) + A(q'))
// over its mirrored cells stays below this (exact symmetry gives 0; subsampling and
// float rounding give a few per cent).
constexpr double kAsymmetryLimit = 0.25;
constexpr std::size_t kSpareCounts = 8;  // the widest vector's lanes

struct Box {
  int x0, y0, w, h;
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
};

// std::llround (halves away from zero) without the library call, for |v| < 2^62: v
// minus its truncation is exact, so the result is the same integer.
inline std::int64_t roundHalfAway(double v) {
  std::int64_t t = static_cast<std::int64_t>(v);
  const double frac = v - static_cast<double>(t);
  if (frac >= 0.5) ++t;
  if (frac <= -0.5) --t;
  return t;
}

// The cells of a ray that lie in the box: cell i (0 <= i < count) is
// ((x + i sx) >> 16, (y + i sy) >> 16) in 16.16 fixed point.
using Ray = BennettWorkspace::Ray;

// A ray from its first step (x, y) and step (sx, sy) in 16.16 fixed point over steps
// 0..steps, reduced to the steps inside the box. Both coordinates are monotonic in the
// step, so the steps inside form one run: its ends are found here (rounding at the box
// edge moves them by a cell at most) and the run is counted without tests. False when
// no step is inside.
inline bool runInBox(const Box& box, std::int64_t x, std::int64_t y, std::int64_t sx, std::int64_t sy, int steps,
                     Ray& ray) {
  const unsigned w = static_cast<unsigned>(box.w), h = static_cast<unsigned>(box.h);
  auto inside = [&](int i) {
    const unsigned cx = static_cast<unsigned>((x + i * sx) >> 16), cy = static_cast<unsigned>((y + i * sy) >> 16);
    return cx < w && cy < h;
  };
  int first = 0, last = steps;
  while (first <= last && !inside(first)) ++first;
  while (last >= first && !inside(last)) --last;
  if (first > last) return false;
  // Inside the box the coordinates and steps fit in int32 (|step| <= one cell).
  ray = Ray{static_cast<std::int32_t>(x + first * sx), static_cast<std::int32_t>(y + first * sy),
            static_cast<std::int32_t>(sx), static_cast<std::int32_t>(sy), last - first + 1};
  return true;
}

// 16.16 fixed point, the first step offset by half a cell so that truncation rounds to
// the nearest cell.
constexpr double kFixedOne = 65536.0;

// The ray from m along u (unit), clipped to the box, in steps of one cell along the
// dominant axis, so no cell is counted twice. False when no cell is in the box.
inline bool clipRay(const Box& box, double mx, double my, double ux, double uy, Ray& ray) {
  double tmax = std::numeric_limits<double>::infinity();
  // The box in cell-centre coordinates: [0, w-1] x [0, h-1], widened by half a cell.
  const double lo_x = -0.5, hi_x = box.w - 0.5, lo_y = -0.5, hi_y = box.h - 0.5;
  if (mx < lo_x || mx > hi_x || my < lo_y || my > hi_y) return false;
  if (ux > 0) tmax = std::min(tmax, (hi_x - mx) / ux);
  if (ux < 0) tmax = std::min(tmax, (lo_x - mx) / ux);
  if (uy > 0) tmax = std::min(tmax, (hi_y - my) / uy);
  if (uy < 0) tmax = std::min(tmax, (lo_y - my) / uy);
  const double step = 1.0 / std::max(std::abs(ux), std::abs(uy));
  const int steps = static_cast<int>(tmax / step);
  const std::int64_t x = static_cast<std::int64_t>((mx + 0.5) * kFixedOne);
  const std::int64_t y = static_cast<std::int64_t>((my + 0.5) * kFixedOne);
  return runInBox(box, x, y, roundHalfAway(ux * step * kFixedOne), roundHalfAway(uy * step * kFixedOne), steps, ray);
}

// The sampled pixels in box coordinates with the right-hand side c of their tangent
// line g . X = c, as arrays (ws.points: x, y, gx, gy, c, each of m doubles).
struct PointArrays {
  const double *x, *y, *gx, *gy, *c;
};

// A parallel-tangent pair: every ellipse of the family is centred at M.
inline void voteMidpoint(std::uint32_t* acc, const Box& box, double mx, double my) {
  const int cx = static_cast<int>(roundHalfAway(mx)), cy = static_cast<int>(roundHalfAway(my));
  if (box.contains(cx, cy)) ++acc[static_cast<std::size_t>(cy) * box.w + cx];
}

// The pairs (i, j), j in [j, m): a pair votes when both gradients point across the
// chord to the same side of the curve (the sign condition on lambda of the thesis);
// its ray runs from the chord's midpoint M away from T, the tangents' intersection.
// Rays are appended to rays[ray_count...]; returns the pairs that voted.
std::size_t scalarPairs(const PointArrays& p, std::size_t i, std::size_t j, std::size_t m, const Box& box,
                        std::uint32_t* acc, Ray* rays, std::size_t& ray_count) {
  const double x1 = p.x[i], y1 = p.y[i], g1x = p.gx[i], g1y = p.gy[i];
  const double c1 = p.c[i];  // tangent line I1: g1 . X = c1
  std::size_t pairs = 0;
  for (; j < m; ++j) {
    const double x2 = p.x[j], y2 = p.y[j], g2x = p.gx[j], g2y = p.gy[j];
    const double dx = x2 - x1, dy = y2 - y1;
    const double s1 = g1x * dx + g1y * dy, s2 = -(g2x * dx + g2y * dy);
    if (!(s1 * s2 > 0.0)) continue;
    const double mx = 0.5 * (x1 + x2), my = 0.5 * (y1 + y2);
    const double det = g1x * g2y - g1y * g2x;
    ++pairs;
    if (det == 0.0) {
      voteMidpoint(acc, box, mx, my);
      continue;
    }
    const double c2 = p.c[j];
    const double tx = (c1 * g2y - c2 * g1y) / det, ty = (g1x * c2 - g2x * c1) / det;
    const double ux = mx - tx, uy = my - ty;
    const double len2 = ux * ux + uy * uy;
    if (!(len2 > 1e-18)) continue;
    const double inv = 1.0 / std::sqrt(len2);
    ray_count += clipRay(box, mx, my, ux * inv, uy * inv, rays[ray_count]);
  }
  return pairs;
}

#if defined(__SSE2__)
namespace sse2 {
struct Ops {
  using V = __m128i;
  static constexpr int kLanes = 4;
  static V set1(std::int32_t v) { return _mm_set1_epi32(v); }
  static V ramp(std::int32_t base, std::int32_t step) {  // base + k step in lane k
    return _mm_setr_epi32(base, base + step, base + 2 * step, base + 3 * step);
  }
  static V add(V a, V b) { return _mm_add_epi32(a, b); }
  static V bitOr(V a, V b) { return _mm_or_si128(a, b); }
  static V bitAnd(V a, V b) { return _mm_and_si128(a, b); }
  static V shiftRight16(V a) { return _mm_srli_epi32(a, 16); }
  static V maddInt16(V a, V b) { return _mm_madd_epi16(a, b); }
  static V greater(V a, V b) { return _mm_cmpgt_epi32(a, b); }
  static V select(V mask, V a, V b) { return _mm_or_si128(_mm_and_si128(mask, a), _mm_andnot_si128(mask, b)); }
  static V max(V a, V b) { return select(greater(a, b), a, b); }  // signed: counts stay below 2^31
  static int equalMask(V a, V b) { return _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(a, b))); }
  template <class T>
  static V load(const T* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
  template <class T>
  static void store(T* p, V v) { _mm_storeu_si128(reinterpret_cast<__m128i*>(p), v); }
};
#include "core/ellipse/bennett_rays_pass.inc"
}  // namespace sse2

// The same text compiled for AVX2 (called only where the processor has it).
IMAGEPRO_AVX2_BEGIN
namespace avx2 {
struct Ops {
  using V = __m256i;
  static constexpr int kLanes = 8;
  static V set1(std::int32_t v) { return _mm256_set1_epi32(v); }
  static V ramp(std::int32_t base, std::int32_t step) {
    return _mm256_add_epi32(_mm256_set1_epi32(base),
                            _mm256_mullo_epi32(_mm256_set1_epi32(step), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  }
  static V add(V a, V b) { return _mm256_add_epi32(a, b); }
  static V bitOr(V a, V b) { return _mm256_or_si256(a, b); }
  static V bitAnd(V a, V b) { return _mm256_and_si256(a, b); }
  static V shiftRight16(V a) { return _mm256_srli_epi32(a, 16); }
  static V maddInt16(V a, V b) { return _mm256_madd_epi16(a, b); }
  static V greater(V a, V b) { return _mm256_cmpgt_epi32(a, b); }
  static V select(V mask, V a, V b) { return _mm256_blendv_epi8(b, a, mask); }
  static V max(V a, V b) { return _mm256_max_epi32(a, b); }  // signed, as with SSE2
  static int equalMask(V a, V b) { return _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(a, b))); }
  template <class T>
  static V load(const T* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
  template <class T>
  static void store(T* p, V v) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v); }
};
#include "core/ellipse/bennett_rays_pass.inc"

// scalarPairs on four pairs per step: the same operations in the same order on every
// lane (no fused multiply-add), so every lane's ray is the scalar one to the bit; the
// run of each ray inside the box is found per lane as there. Returns the pairs that
// voted; j ends at the first of the (fewer than four) pairs left to scalarPairs.
std::size_t vectorPairs(const PointArrays& p, std::size_t i, std::size_t& j, std::size_t m, const Box& box,
                        std::uint32_t* acc, Ray* rays, std::size_t& ray_count) {
  const __m256d x1 = _mm256_set1_pd(p.x[i]), y1 = _mm256_set1_pd(p.y[i]);
  const __m256d g1x = _mm256_set1_pd(p.gx[i]), g1y = _mm256_set1_pd(p.gy[i]), c1 = _mm256_set1_pd(p.c[i]);
  const __m256d zero = _mm256_setzero_pd(), half = _mm256_set1_pd(0.5), one = _mm256_set1_pd(1.0);
  const __m256d sign = _mm256_set1_pd(-0.0), tiny = _mm256_set1_pd(1e-18);
  const __m256d infinity = _mm256_set1_pd(std::numeric_limits<double>::infinity());
  const __m256d fixed_one = _mm256_set1_pd(kFixedOne);
  const __m256d lo = _mm256_set1_pd(-0.5), hi_x = _mm256_set1_pd(box.w - 0.5), hi_y = _mm256_set1_pd(box.h - 0.5);
  // Truncation, then halves away from zero (roundHalfAway).
  auto roundHalfAway4 = [&](__m256d v) {
    const __m256d t = _mm256_round_pd(v, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
    const __m256d frac = _mm256_sub_pd(v, t);
    const __m256d up = _mm256_and_pd(_mm256_cmp_pd(frac, half, _CMP_GE_OQ), one);
    const __m256d down = _mm256_and_pd(_mm256_cmp_pd(frac, _mm256_xor_pd(half, sign), _CMP_LE_OQ), one);
    return _mm256_cvttpd_epi32(_mm256_sub_pd(_mm256_add_pd(t, up), down));
  };
  // The distance along u to where the ray leaves [lo, hi] in one coordinate (infinite
  // when u is 0 in it).
  auto exitDistance = [&](__m256d u, __m256d m_, __m256d hi) {
    const __m256d positive = _mm256_cmp_pd(u, zero, _CMP_GT_OQ);
    const __m256d d = _mm256_div_pd(_mm256_sub_pd(_mm256_blendv_pd(lo, hi, positive), m_), u);
    return _mm256_blendv_pd(d, infinity, _mm256_cmp_pd(u, zero, _CMP_EQ_OQ));
  };
  std::size_t pairs = 0;
  alignas(32) double mid_x[4], mid_y[4];
  alignas(16) std::int32_t fx[4], fy[4], fsx[4], fsy[4], fsteps[4];
  for (; j + 4 <= m; j += 4) {
    const __m256d x2 = _mm256_loadu_pd(p.x + j), y2 = _mm256_loadu_pd(p.y + j);
    const __m256d g2x = _mm256_loadu_pd(p.gx + j), g2y = _mm256_loadu_pd(p.gy + j);
    const __m256d dx = _mm256_sub_pd(x2, x1), dy = _mm256_sub_pd(y2, y1);
    const __m256d s1 = _mm256_add_pd(_mm256_mul_pd(g1x, dx), _mm256_mul_pd(g1y, dy));
    const __m256d s2 = _mm256_xor_pd(_mm256_add_pd(_mm256_mul_pd(g2x, dx), _mm256_mul_pd(g2y, dy)), sign);
    const __m256d vote = _mm256_cmp_pd(_mm256_mul_pd(s1, s2), zero, _CMP_GT_OQ);
    const int votes = _mm256_movemask_pd(vote);
    if (votes == 0) continue;
    pairs += static_cast<std::size_t>(__builtin_popcount(static_cast<unsigned>(votes)));
    const __m256d mx = _mm256_mul_pd(half, _mm256_add_pd(x1, x2)), my = _mm256_mul_pd(half, _mm256_add_pd(y1, y2));
    const __m256d det = _mm256_sub_pd(_mm256_mul_pd(g1x, g2y), _mm256_mul_pd(g1y, g2x));
    const __m256d parallel = _mm256_cmp_pd(det, zero, _CMP_EQ_OQ);
    const int parallels = votes & _mm256_movemask_pd(parallel);
    if (parallels != 0) {
      _mm256_store_pd(mid_x, mx);
      _mm256_store_pd(mid_y, my);
      for (int k = 0; k < 4; ++k)
        if (parallels >> k & 1) voteMidpoint(acc, box, mid_x[k], mid_y[k]);
    }
    const __m256d c2 = _mm256_loadu_pd(p.c + j);
    const __m256d tx = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(c1, g2y), _mm256_mul_pd(c2, g1y)), det);
    const __m256d ty = _mm256_div_pd(_mm256_sub_pd(_mm256_mul_pd(g1x, c2), _mm256_mul_pd(g2x, c1)), det);
    __m256d ux = _mm256_sub_pd(mx, tx), uy = _mm256_sub_pd(my, ty);
    const __m256d len2 = _mm256_add_pd(_mm256_mul_pd(ux, ux), _mm256_mul_pd(uy, uy));
    const __m256d in_box = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(mx, lo, _CMP_GE_OQ), _mm256_cmp_pd(mx, hi_x, _CMP_LE_OQ)),
                                         _mm256_and_pd(_mm256_cmp_pd(my, lo, _CMP_GE_OQ), _mm256_cmp_pd(my, hi_y, _CMP_LE_OQ)));
    const int clipped = votes & ~parallels & _mm256_movemask_pd(_mm256_and_pd(_mm256_cmp_pd(len2, tiny, _CMP_GT_OQ), in_box));
    if (clipped == 0) continue;
    const __m256d inv = _mm256_div_pd(one, _mm256_sqrt_pd(len2));
    ux = _mm256_mul_pd(ux, inv);
    uy = _mm256_mul_pd(uy, inv);
    const __m256d tmax = _mm256_min_pd(exitDistance(ux, mx, hi_x), exitDistance(uy, my, hi_y));
    const __m256d step = _mm256_div_pd(one, _mm256_max_pd(_mm256_andnot_pd(sign, ux), _mm256_andnot_pd(sign, uy)));
    _mm_store_si128(reinterpret_cast<__m128i*>(fsteps), _mm256_cvttpd_epi32(_mm256_div_pd(tmax, step)));
    _mm_store_si128(reinterpret_cast<__m128i*>(fx), _mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_add_pd(mx, half), fixed_one)));
    _mm_store_si128(reinterpret_cast<__m128i*>(fy), _mm256_cvttpd_epi32(_mm256_mul_pd(_mm256_add_pd(my, half), fixed_one)));
    _mm_store_si128(reinterpret_cast<__m128i*>(fsx), roundHalfAway4(_mm256_mul_pd(_mm256_mul_pd(ux, step), fixed_one)));
    _mm_store_si128(reinterpret_cast<__m128i*>(fsy), roundHalfAway4(_mm256_mul_pd(_mm256_mul_pd(uy, step), fixed_one)));
    for (int k = 0; k < 4; ++k)
      if (clipped >> k & 1) ray_count += runInBox(box, fx[k], fy[k], fsx[k], fsy[k], fsteps[k], rays[ray_count]);
  }
  return pairs;
}
}  // namespace avx2
IMAGEPRO_AVX2_END

void voteRays(std::uint32_t* acc, const Box& box, std::span<const Ray> rays, std::int32_t* cells) {
  const std::int32_t spare = box.w * box.h;
  if (simdAllows(SimdLevel::Avx2))
    avx2::voteRays(acc, box.w, spare, rays, cells);
  else
    sse2::voteRays(acc, box.w, spare, rays, cells);
}
std::uint32_t maxCount(const std::uint32_t* acc, std::size_t n) {
  return simdAllows(SimdLevel::Avx2) ? avx2::maxCount(acc, n) : sse2::maxCount(acc, n);
}
std::size_t firstIndexOf(const std::uint32_t* acc, std::size_t n, std::uint32_t value) {
  return simdAllows(SimdLevel::Avx2) ? avx2::firstIndexOf(acc, n, value) : sse2::firstIndexOf(acc, n, value);
}
#else
void voteRays(std::uint32_t* acc, const Box& box, std::span<const Ray> rays, std::int32_t*) {
  for (const Ray& r : rays)
    for (std::int32_t k = 0, x = r.x, y = r.y; k < r.count; ++k, x += r.sx, y += r.sy)
      ++acc[(y >> 16) * box.w + (x >> 16)];
}
std::uint32_t maxCount(const std::uint32_t* acc, std::size_t n) { return *std::max_element(acc, acc + n); }
std::size_t firstIndexOf(const std::uint32_t* acc, std::size_t n, std::uint32_t value) {
  return static_cast<std::size_t>(std::find(acc, acc + n, value) - acc);
}
#endif

// Samples `keep` of the `usable` pixels (those with a gradient) and accumulates every
// pair's ray into ws.accumulator over `box`; returns the pairs that voted. The sample is
// a uniformly random subset (selection sampling, fixed seed): a path's pixels come in
// breadth-first order, which alternates between the two fronts of a contour, so an even
// stride through the list could take one side of the curve only.
std::size_t accumulatePairs(std::span<const EdgePixel> path, std::size_t usable, std::size_t keep, const Box& box,
                            BennettWorkspace& ws) {
  ws.sample.clear();
  std::minstd_rand rng(static_cast<std::minstd_rand::result_type>(usable * 2654435761u + keep));
  std::size_t seen = 0;
  for (std::uint32_t i = 0; i < path.size() && ws.sample.size() < keep; ++i) {
    if (path[i].gx == 0 && path[i].gy == 0) continue;
    // Take this pixel with probability (still needed) / (still available).
    const std::size_t needed = keep - ws.sample.size(), available = usable - seen;
    if (needed == available || static_cast<std::size_t>(rng() % available) < needed) ws.sample.push_back(i);
    ++seen;
  }
  // The box's cells and kSpareCounts more for the lanes past a ray's end (bennett_rays_pass.inc),
  // dropped when the counting is done.
  const std::size_t grid = static_cast<std::size_t>(box.w) * box.h;
  ws.box = {box.x0, box.y0, box.w, box.h};
  ws.accumulator.assign(grid + kSpareCounts, 0u);
  std::uint32_t* acc = ws.accumulator.data();
  const std::size_t m = ws.sample.size();
  // The sampled pixels in box coordinates, as doubles, with the right-hand side c of
  // their tangent line g . X = c: converted once, not once per pair.
  ws.points.resize(5 * m);
  double* const coords = ws.points.data();
  const PointArrays points{coords, coords + m, coords + 2 * m, coords + 3 * m, coords + 4 * m};
  for (std::size_t i = 0; i < m; ++i) {
    const EdgePixel& a = path[ws.sample[i]];
    const double x = a.x - box.x0, y = a.y - box.y0, gx = a.gx, gy = a.gy;
    coords[i] = x;
    coords[m + i] = y;
    coords[2 * m + i] = gx;
    coords[3 * m + i] = gy;
    coords[4 * m + i] = gx * x + gy * y;
  }
  // The rays of one pixel's pairs are clipped first and counted after: the clipping's
  // chain of divisions for one pair then overlaps the next pair's instead of waiting
  // for a counting loop.
  ws.rays.resize(m);
  ws.cells.resize(static_cast<std::size_t>(std::max(box.w, box.h)) + 8);  // a ray's cells, whole vectors
#if defined(__SSE2__)
  const bool wide = simdAllows(SimdLevel::Avx2);
#endif
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < m; ++i) {
    std::size_t rays = 0, j = i + 1;
#if defined(__SSE2__)
    if (wide) pairs += avx2::vectorPairs(points, i, j, m, box, acc, ws.rays.data(), rays);
#endif
    pairs += scalarPairs(points, i, j, m, box, acc, ws.rays.data(), rays);
    voteRays(acc, box, std::span<const Ray>(ws.rays.data(), rays), ws.cells.data());
  }
  ws.accumulator.resize(grid);  // keeps the capacity
  return pairs;
}

double maxVotes(const BennettWorkspace& ws) { return maxCount(ws.accumulator.data(), ws.accumulator.size()); }

}  // namespace

Status bennettAccumulate(std::span<const EdgePixel> path, int max_points, BennettWorkspace& ws, BennettResult& out,
                         double screen_peak_fraction) {
  out = BennettResult{};
  std::size_t usable = 0;
  for (const EdgePixel& p : path) usable += (p.gx != 0 || p.gy != 0);
  if (usable < 6) return Status::TooFewPoints;
  const std::size_t keep = max_points > 0 ? std::min<std::size_t>(usable, static_cast<std::size_t>(max_points)) : usable;
  const double all_pairs = 0.5 * static_cast<double>(usable) * static_cast<double>(usable - 1);
  auto pairsOf = [](std::size_t m) { return 0.5 * static_cast<double>(m) * static_cast<double>(m - 1); };

  int minx = path[0].x, maxx = minx, miny = path[0].y, maxy = miny;
  for (const EdgePixel& p : path) {
    minx = std::min<int>(minx, p.x);
    maxx = std::max<int>(maxx, p.x);
    miny = std::min<int>(miny, p.y);
    maxy = std::max<int>(maxy, p.y);
  }
  const Box box{minx - kMargin, miny - kMargin, maxx - minx + 1 + 2 * kMargin, maxy - miny + 1 + 2 * kMargin};

  // Coarse screen: on half the points (a quarter of the pairs) the peak of a path that
  // passes gathers about its full share; far below, the full accumulation is skipped.
  if (screen_peak_fraction > 0.0 && keep >= kMinScreenPoints) {
    out.pairs = accumulatePairs(path, usable, keep / 2, box, ws);
    const double fraction = maxVotes(ws) / pairsOf(ws.sample.size());
    if (fraction < kScreenShare * screen_peak_fraction) {
      out.peak_fraction = fraction;
      out.score = fraction * all_pairs;
      return out.pairs == 0 ? Status::NoTarget : Status::Ok;  // symmetry_px 0: never accepted
    }
  }
  out.pairs = accumulatePairs(path, usable, keep, box, ws);
  if (out.pairs == 0) return Status::NoTarget;
  const std::uint32_t* acc = ws.accumulator.data();
  // Votes are counted per cell; the weight of a sampled pair scales the scores after.
  const double weight = all_pairs / pairsOf(ws.sample.size());

  // Absolute peak.
  const std::size_t best = firstIndexOf(acc, ws.accumulator.size(), maxCount(acc, ws.accumulator.size()));
  const int px = static_cast<int>(best % box.w), py = static_cast<int>(best / box.w);
  const double peak = acc[best];  // votes; the score is in all-pairs units
  if (!(peak > 0.0)) return Status::NoTarget;
  out.score = weight * peak;
  out.peak_fraction = out.score / all_pairs;
  const int border = std::min({px, py, box.w - 1 - px, box.h - 1 - py});  // for the rings of the quality

  // Centre of symmetry: the box's centre when the peak is within kSnap cells of it (the
  // rays' rounding can move the peak of a symmetric path by a cell), else the peak.
  // Both are on the cell grid or halfway between cells: mirror of cell q = 2c - q.
  int twice_cx = 2 * px, twice_cy = 2 * py;  // 2c in cell units
  if (std::abs(2 * px - (box.w - 1)) <= 2 * kSnap && std::abs(2 * py - (box.h - 1)) <= 2 * kSnap) {
    twice_cx = box.w - 1;
    twice_cy = box.h - 1;
  }
  const int best_sx = twice_cx - 2 * px, best_sy = twice_cy - 2 * py;
  out.cx = box.x0 + 0.5 * twice_cx;
  out.cy = box.y0 + 0.5 * twice_cy;

  // Rings about the peak out to the farthest border: mean score (quality) and point
  // symmetry about the centre of symmetry, cells outside the box counting as empty. A
  // point-symmetric path has a box symmetric about its centre, so the rings stay
  // symmetric to the end; a peak off the box's centre loses its symmetry at the nearest
  // border, where the mirrored cells leave the box (thesis rule 1).
  // Per ring r: [0] sum of scores, [1] cells, [2] sum |A(q) - A(q')|, [3] sum A(q) + A(q').
  // The sums are of integer counts, exact in any order.
  const int reach = std::max({px, py, box.w - 1 - px, box.h - 1 - py});
  const std::size_t rings = static_cast<std::size_t>(reach) + 1;
  out.border_distance_px = reach;
  ws.rings.assign(4 * rings, 0);
  std::int64_t* ring_sum = ws.rings.data();
  std::int64_t* ring_count = ring_sum + rings;
  std::int64_t* ring_diff = ring_count + rings;
  std::int64_t* ring_both = ring_diff + rings;
  // Only cells where A(q) or its mirror A(q') lies in the box add anything (the cells
  // counted for the mean, within `border` of the peak, lie in it): the rows and columns
  // of offsets d where either does. The mirror's offset differs by at most 2 kSnap, so
  // each range is one interval, and it contains 0.
  const int dx_lo = std::max(-reach, std::min(-px, px + best_sx - (box.w - 1)));
  const int dx_hi = std::min(reach, std::max(box.w - 1 - px, px + best_sx));
  const int dy_lo = std::max(-reach, std::min(-py, py + best_sy - (box.h - 1)));
  const int dy_hi = std::min(reach, std::max(box.h - 1 - py, py + best_sy));
  for (int dy = dy_lo; dy <= dy_hi; ++dy) {
    const int uy = py + dy, vy = py + best_sy - dy;
    const std::uint32_t* u_row = uy >= 0 && uy < box.h ? acc + static_cast<std::ptrdiff_t>(uy) * box.w : nullptr;
    const std::uint32_t* v_row = vy >= 0 && vy < box.h ? acc + static_cast<std::ptrdiff_t>(vy) * box.w : nullptr;
    auto addCell = [&](int dx, int r) {
      const int ux = px + dx, vx = px + best_sx - dx;
      const std::int64_t u = u_row && ux >= 0 && ux < box.w ? u_row[ux] : 0;
      const std::int64_t v = v_row && vx >= 0 && vx < box.w ? v_row[vx] : 0;
      if (r <= border) {
        ring_sum[r] += u;
        ++ring_count[r];
      }
      ring_diff[r] += u > v ? u - v : v - u;
      ring_both[r] += u + v;
    };
    // The ring of offset d is lround(|d|): the r with r^2 - r < |d|^2 <= r^2 + r (no
    // integer |d|^2 lies on a half-integer radius), found by stepping r outwards along
    // each half row from |dy|.
    const std::int64_t dy2 = static_cast<std::int64_t>(dy) * dy;
    for (int side = 1; side >= -1; side -= 2) {
      const int end = side > 0 ? dx_hi : -dx_lo;
      std::int64_t r = std::abs(dy);
      for (int t = side > 0 ? 0 : 1; t <= end; ++t) {
        const std::int64_t d2 = dy2 + static_cast<std::int64_t>(t) * t;
        while (d2 > r * r + r) ++r;
        if (r > reach) break;
        addCell(side * t, static_cast<int>(r));
      }
    }
  }
  const double half = 0.5 * peak;
  out.half_radius_px = border;  // when the mean never falls to half inside the box
  double prev = peak;
  for (int r = 1; r <= border; ++r) {
    const double mean = static_cast<double>(ring_sum[r]) / static_cast<double>(ring_count[r]);
    if (mean <= half) {
      out.half_radius_px = (r - 1) + (prev - half) / (prev - mean);
      break;
    }
    prev = mean;
  }
  out.quality = out.score / std::sqrt(std::max(out.half_radius_px, 0.25));
  out.symmetry_px = reach + 1;  // symmetric out to the farthest border
  for (int r = 1; r <= reach; ++r) {
    if (ring_both[r] > 0 && static_cast<double>(ring_diff[r]) / static_cast<double>(ring_both[r]) > kAsymmetryLimit) {
      out.symmetry_px = r;
      break;
    }
  }
  return Status::Ok;
}

bool bennettAccepts(const EllipseOptions& o, const BennettResult& r) {
  if (r.symmetry_px <= r.border_distance_px) return false;                                // rule 1
  if (r.quality < o.bennett_min_quality || r.quality > o.bennett_max_quality) return false;  // rule 2
  if (r.score < o.bennett_min_score || r.score > o.bennett_max_score) return false;          // rule 3
  if (r.peak_fraction < o.bennett_min_peak_fraction) return false;
  return true;
}

}  // namespace imagepro
