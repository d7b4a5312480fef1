#pragma once
// Pieces shared by the ellipse stage's passes over the edge pixels of a path (internal
// to the module): the bounding box of a path, with SSE2 one pixel as four int32 lanes
// (x, y, gx, gy), so two sums of a pass share one instruction, and the path summary's
// sums with its bounding box in one pass (integer multiply-adds on two pixels per SSE2
// instruction, four where the processor has AVX2).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/common/contract.h"
#include "core/common/simd_level.h"
#include "core/edges/edge_list.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace imagepro::pixel_passes {

static_assert(sizeof(EdgePixel) == 4 * sizeof(std::int16_t), "EdgePixel is read as four int16 lanes");

struct Bounds {
  int min_x = 0, max_x = 0, min_y = 0, max_y = 0;
};

#if defined(__SSE2__)
// Pixel p as the int32 lanes (x, y, gx, gy).
inline __m128i loadPixel(const EdgePixel& p) {
  const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(&p));
  return _mm_srai_epi32(_mm_unpacklo_epi16(v, v), 16);
}
#endif

// The smallest and largest x and y of a non-empty set of pixels.
inline Bounds bounds(std::span<const EdgePixel> points) {
#if defined(__SSE2__)
  // Two pixels per load, as eight int16 lanes x, y, gx, gy, x, y, gx, gy: lanes 0 and
  // 4 hold x, lanes 1 and 5 hold y.
  auto load2 = [](const EdgePixel* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); };
  auto load1 = [](const EdgePixel* p) {
    const __m128i v = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
    return _mm_unpacklo_epi64(v, v);
  };
  const std::size_t n = points.size();
  std::size_t k = n % 2;
  __m128i lo = k != 0 ? load1(points.data()) : load2(points.data());
  __m128i hi = lo;
  for (; k < n; k += 2) {
    const __m128i v = load2(points.data() + k);
    lo = _mm_min_epi16(lo, v);
    hi = _mm_max_epi16(hi, v);
  }
  alignas(16) std::int16_t l[8], h[8];
  _mm_store_si128(reinterpret_cast<__m128i*>(l), lo);
  _mm_store_si128(reinterpret_cast<__m128i*>(h), hi);
  return {std::min(l[0], l[4]), std::max(h[0], h[4]), std::min(l[1], l[5]), std::max(h[1], h[5])};
#else
  Bounds b{points[0].x, points[0].x, points[0].y, points[0].y};
  for (const EdgePixel& p : points) {
    b.min_x = std::min<int>(b.min_x, p.x);
    b.max_x = std::max<int>(b.max_x, p.x);
    b.min_y = std::min<int>(b.min_y, p.y);
    b.max_y = std::max<int>(b.max_y, p.y);
  }
  return b;
#endif
}

// The summary sums of a path about an origin (ox, oy), exact integers: offsets
// x = px - ox, y = py - oy and gradients g.
struct PathSums {
  std::int64_t x = 0, y = 0, xx_yy = 0, gx = 0, gy = 0, g_dot = 0;  // g_dot: gx x + gy y
  Bounds bounds;
};

namespace detail {

inline void addScalar(const EdgePixel& p, int ox, int oy, PathSums& s) {
  const std::int64_t x = p.x - ox, y = p.y - oy;
  s.x += x;
  s.y += y;
  s.xx_yy += x * x + y * y;
  s.gx += p.gx;
  s.gy += p.gy;
  s.g_dot += p.gx * x + p.gy * y;
  s.bounds.min_x = std::min<int>(s.bounds.min_x, p.x);
  s.bounds.max_x = std::max<int>(s.bounds.max_x, p.x);
  s.bounds.min_y = std::min<int>(s.bounds.min_y, p.y);
  s.bounds.max_y = std::max<int>(s.bounds.max_y, p.y);
}

// The vector passes take blocks of kSumBlock pixels and multiply-add int16 lanes into
// int32 sums: exact while every offset and gradient of the block is below kSumReach in
// magnitude (each int32 lane gathers at most kSumBlock / 2 pixels of at most
// 2 kSumReach^2: 2^9 * 2^21 = 2^30). A block beyond that is summed again in 64 bits.
constexpr std::size_t kSumBlock = 1024;
constexpr int kSumReach = 1 << 10;

inline bool withinReach(const std::int16_t* lo, const std::int16_t* hi, int lanes, int ox, int oy) {
  for (int k = 0; k < lanes; k += 4) {
    if (hi[k] - ox >= kSumReach || ox - lo[k] >= kSumReach || hi[k + 1] - oy >= kSumReach ||
        oy - lo[k + 1] >= kSumReach)
      return false;
    for (int j = 2; j < 4; ++j)
      if (hi[k + j] >= kSumReach || lo[k + j] <= -kSumReach) return false;
  }
  return true;
}

// Adds int32 lanes (even: first sum, odd: second) into two 64-bit sums.
inline void addPairs(const std::int32_t* v, int lanes, std::int64_t& even, std::int64_t& odd) {
  for (int k = 0; k < lanes; k += 2) {
    even += v[k];
    odd += v[k + 1];
  }
}

#if defined(__SSE2__)
namespace sse2 {
struct Ops {
  using V = __m128i;
  static V zero() { return _mm_setzero_si128(); }
  static V origin(int ox, int oy) {
    const short x = static_cast<short>(ox), y = static_cast<short>(oy);
    return _mm_setr_epi16(x, y, 0, 0, x, y, 0, 0);
  }
  static V pairs(int v) { return _mm_set1_epi32(v); }
  static V load(const EdgePixel* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
  static V min(V a, V b) { return _mm_min_epi16(a, b); }
  static V max(V a, V b) { return _mm_max_epi16(a, b); }
  static V sub(V a, V b) { return _mm_sub_epi16(a, b); }
  static V add(V a, V b) { return _mm_add_epi32(a, b); }
  static V madd(V a, V b) { return _mm_madd_epi16(a, b); }
  static V dupPosition(V d) { return _mm_shuffle_epi32(d, _MM_SHUFFLE(2, 2, 0, 0)); }
  template <class T>
  static void store(T* out, V v) { _mm_store_si128(reinterpret_cast<__m128i*>(out), v); }
};
#include "core/ellipse/path_sums_pass.inc"
}  // namespace sse2

// The same text compiled for AVX2 (called only where the processor has it).
IMAGEPRO_AVX2_BEGIN
namespace avx2 {
struct Ops {
  using V = __m256i;
  static V zero() { return _mm256_setzero_si256(); }
  static V origin(int ox, int oy) {
    const short x = static_cast<short>(ox), y = static_cast<short>(oy);
    return _mm256_setr_epi16(x, y, 0, 0, x, y, 0, 0, x, y, 0, 0, x, y, 0, 0);
  }
  static V pairs(int v) { return _mm256_set1_epi32(v); }
  static V load(const EdgePixel* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
  static V min(V a, V b) { return _mm256_min_epi16(a, b); }
  static V max(V a, V b) { return _mm256_max_epi16(a, b); }
  static V sub(V a, V b) { return _mm256_sub_epi16(a, b); }
  static V add(V a, V b) { return _mm256_add_epi32(a, b); }
  static V madd(V a, V b) { return _mm256_madd_epi16(a, b); }
  static V dupPosition(V d) { return _mm256_shuffle_epi32(d, _MM_SHUFFLE(2, 2, 0, 0)); }
  template <class T>
  static void store(T* out, V v) { _mm256_store_si256(reinterpret_cast<__m256i*>(out), v); }
};
#include "core/ellipse/path_sums_pass.inc"
}  // namespace avx2
IMAGEPRO_AVX2_END
#endif

}  // namespace detail

// The sums and bounding box of a non-empty path about (ox, oy) in one pass.
inline PathSums pathSums(std::span<const EdgePixel> path, int ox, int oy) {
  IMAGEPRO_EXPECTS(!path.empty(), "pathSums of a non-empty path");
  PathSums s;
  s.bounds = {path[0].x, path[0].x, path[0].y, path[0].y};
#if defined(__SSE2__)
  if (simdAllows(SimdLevel::Avx2))
    detail::avx2::sums(path, ox, oy, s);
  else
    detail::sse2::sums(path, ox, oy, s);
#else
  for (const EdgePixel& p : path) detail::addScalar(p, ox, oy, s);
#endif
  return s;
}

}  // namespace imagepro::pixel_passes
