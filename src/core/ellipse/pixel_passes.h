#pragma once
// Pieces shared by the ellipse stage's passes over the edge pixels of a path (internal
// to the module): the bounding box of a path, and with SSE2 one pixel as four int32
// lanes (x, y, gx, gy), so two sums of a pass share one instruction.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "core/edges/edge_list.h"

#if defined(__SSE2__)
#include <emmintrin.h>
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

}  // namespace imagepro::pixel_passes
