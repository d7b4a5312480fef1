// The one pass of pixel_passes::pathSums, written once for both vector widths: included
// by pixel_passes.h into a namespace that defines Ops (the vector type V and its
// operations) and compiled once per width. No include guard, on purpose.
// One pass, W int16 lanes (W / 4 pixels) per step: the lanes hold x, y, gx, gy of
// consecutive pixels; d = pixel - (ox, oy, 0, 0); madd(d, (x, y, x, y)) gives
// (x^2 + y^2, gx x + gy y), madd(d, (1, 0, 1, 0)) gives (x, gx), madd(d, (0, 1, 0, 1))
// gives (y, gy).
inline void sums(std::span<const EdgePixel> path, int ox, int oy, PathSums& s) {
  using V = typename Ops::V;
  constexpr int kLanes = sizeof(V) / sizeof(std::int16_t);
  constexpr std::size_t kPixels = kLanes / 4;
  const V origin = Ops::origin(ox, oy), ones_x = Ops::pairs(1), ones_y = Ops::pairs(1 << 16);
  const std::size_t n = path.size();
  std::size_t i = 0;
  while (i + kPixels <= n) {
    const std::size_t end = i + std::min(kSumBlock, (n - i) / kPixels * kPixels);
    const std::size_t start = i;
    V lo = Ops::load(path.data() + i), hi = lo, q = Ops::zero(), a = q, b = q;
    for (; i < end; i += kPixels) {
      const V v = Ops::load(path.data() + i);
      lo = Ops::min(lo, v);
      hi = Ops::max(hi, v);
      const V d = Ops::sub(v, origin);
      q = Ops::add(q, Ops::madd(d, Ops::dupPosition(d)));
      a = Ops::add(a, Ops::madd(d, ones_x));
      b = Ops::add(b, Ops::madd(d, ones_y));
    }
    alignas(32) std::int16_t l[kLanes], h[kLanes];
    Ops::store(l, lo);
    Ops::store(h, hi);
    if (!withinReach(l, h, kLanes, ox, oy)) {
      for (std::size_t k = start; k < end; ++k) addScalar(path[k], ox, oy, s);
      continue;
    }
    for (int k = 0; k < kLanes; k += 4) {
      s.bounds.min_x = std::min<int>(s.bounds.min_x, l[k]);
      s.bounds.max_x = std::max<int>(s.bounds.max_x, h[k]);
      s.bounds.min_y = std::min<int>(s.bounds.min_y, l[k + 1]);
      s.bounds.max_y = std::max<int>(s.bounds.max_y, h[k + 1]);
    }
    alignas(32) std::int32_t sq[kLanes / 2], sa[kLanes / 2], sb[kLanes / 2];
    Ops::store(sq, q);
    Ops::store(sa, a);
    Ops::store(sb, b);
    addPairs(sq, kLanes / 2, s.xx_yy, s.g_dot);
    addPairs(sa, kLanes / 2, s.x, s.gx);
    addPairs(sb, kLanes / 2, s.y, s.gy);
  }
  for (; i < n; ++i) addScalar(path[i], ox, oy, s);
}

