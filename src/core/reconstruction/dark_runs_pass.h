// The text of the spot search's row scan, included by spot_search.cpp once per vector width
// (SSE2: 16 pixels per comparison; AVX2: 32) inside a namespace that defines
//   struct Ops { kBlock; Level, level(cut), value(level); Block, load(p), min(a, b);
//                dark(block, level); darkMask(p, level) };
// dark and darkMask give bit i set when pixel i of the block (at p) is <= level. Private to
// spot_search.cpp: no include guard, no declarations of its own outside the namespace.

// The first x in [x, x1] with row[x] <= level (Dark) or row[x] > level (!Dark), x1 + 1 if
// none: whole blocks of kBlock pixels are passed over when none of them qualifies. The
// pixels from `lowest` on may be read: the last, partial block is then read as the whole
// block ending at x1, its pixels before x masked off.
template <bool Dark>
inline int firstOf(const std::uint8_t* row, int x, int x1, const Ops::Level& level, int lowest) {
  constexpr int kBlock = Ops::kBlock;
  constexpr unsigned kAll = 0xFFFFFFFFu >> (32 - kBlock);
  auto flags = [&](int at) {
    const unsigned mask = Ops::darkMask(row + at, level);
    return Dark ? mask : mask ^ kAll;
  };
  for (; x + kBlock <= x1 + 1; x += kBlock)
    if (const unsigned mask = flags(x); mask != 0) return x + std::countr_zero(mask);
  if (x <= x1 && x1 + 1 - kBlock >= lowest) {
    const int at = x1 + 1 - kBlock;
    const unsigned mask = flags(at) & (kAll << (x - at));
    return mask != 0 ? at + std::countr_zero(mask) : x1 + 1;
  }
  const std::uint8_t cut = Ops::value(level);
  while (x <= x1 && (row[x] <= cut) != Dark) ++x;
  return x;
}

// Whether any of the n rows (pointers to the same x origin) has a pixel <= level in [x0, x1]:
// their minimum tested kBlock pixels per step (the last, partial block as the whole block
// ending at x1 when the pixels from `lowest` on allow, else pixel by pixel).
inline bool anyDark(const std::uint8_t* const* rows, int n, int x0, int x1, std::uint8_t cut, int lowest) {
  constexpr int kBlock = Ops::kBlock;
  const Ops::Level level = Ops::level(cut);
  auto blockHasDark = [&](int at) {
    Ops::Block m = Ops::load(rows[0] + at);
    for (int k = 1; k < n; ++k) m = Ops::min(m, Ops::load(rows[k] + at));
    return Ops::dark(m, level);
  };
  int x = x0;
  for (; x + kBlock <= x1 + 1; x += kBlock)
    if (blockHasDark(x) != 0) return true;
  if (x > x1) return false;
  if (x1 + 1 - kBlock >= lowest) {
    const int at = x1 + 1 - kBlock;
    return (blockHasDark(at) & (0xFFFFFFFFu >> (32 - kBlock) << (x - at))) != 0;
  }
  for (; x <= x1; ++x)
    for (int k = 0; k < n; ++k)
      if (rows[k][x] <= cut) return true;
  return false;
}

// The dark runs (pixels <= level) of row[x0..x1] as inclusive bounds, start and end in turn,
// into `bounds` (room for x1 - x0 + 2 values); returns the number of runs.
inline int darkRuns(const std::uint8_t* row, int x0, int x1, std::uint8_t cut, int lowest, int* bounds) {
  const Ops::Level level = Ops::level(cut);
  int n = 0;
  for (int x = x0; x <= x1;) {
    x = firstOf<true>(row, x, x1, level, lowest);
    if (x > x1) break;
    const int start = x;
    x = firstOf<false>(row, x, x1, level, lowest);
    bounds[2 * n] = start;
    bounds[2 * n + 1] = x - 1;
    ++n;
  }
  return n;
}
