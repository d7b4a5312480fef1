// Bennett's per-cell loops (internal to bennett.cpp), included once per instruction set
// inside a namespace that defines Ops (the vector type V, kLanes and the lane
// operations). Every instruction set gives the same counts, cell by cell.
//
// A ray's cell k is ((x + k sx) >> 16, (y + k sy) >> 16) in 16.16 fixed point. Inside
// the box both coordinates are below 2^15, so a cell is the int16 pair (row, column) in
// one int32 lane (the row is y >> 16, the column the upper half of x) and one
// multiply-add of int16 pairs by (stride, 1) gives its index row * stride + column:
// the lanes compute the indices of kLanes cells per step, and the counting loop adds
// the votes. Lanes past the ray's end are computed but never counted.

// Adds a vote to every cell of each ray; `cells` holds at least the longest ray's
// count rounded up to kLanes, and acc has kLanes spare counts past its `spare` grid
// cells. The lanes past a ray's end are pointed at the spare counts, one per lane, so
// the counting loop runs over whole vectors without a test per cell and no count is
// incremented twice in a row (which would chain the increments through memory).
inline void voteRays(std::uint32_t* acc, int stride, std::int32_t spare, std::span<const Ray> rays,
                     std::int32_t* cells) {
  const typename Ops::V row_column_weights = Ops::set1((1 << 16) | stride);
  const typename Ops::V column_half = Ops::set1(static_cast<std::int32_t>(0xFFFF0000u));
  const typename Ops::V lane_numbers = Ops::ramp(0, 1), lane_step = Ops::set1(Ops::kLanes);
  const typename Ops::V spare_cells = Ops::ramp(spare, 1);
  for (const Ray& r : rays) {
    const int count = r.count, padded = (count + Ops::kLanes - 1) & -Ops::kLanes;
    const typename Ops::V cell_count = Ops::set1(count);
    typename Ops::V x = Ops::ramp(r.x, r.sx), y = Ops::ramp(r.y, r.sy), lane = lane_numbers;
    const typename Ops::V step_x = Ops::set1(Ops::kLanes * r.sx), step_y = Ops::set1(Ops::kLanes * r.sy);
    for (int k = 0; k < padded; k += Ops::kLanes) {
      const typename Ops::V row_column = Ops::bitOr(Ops::shiftRight16(y), Ops::bitAnd(x, column_half));
      const typename Ops::V index = Ops::maddInt16(row_column, row_column_weights);
      Ops::store(cells + k, Ops::select(Ops::greater(cell_count, lane), index, spare_cells));
      x = Ops::add(x, step_x);
      y = Ops::add(y, step_y);
      lane = Ops::add(lane, lane_step);
    }
    for (int k = 0; k < padded; k += Ops::kLanes)
      for (int j = 0; j < Ops::kLanes; ++j) ++acc[cells[k + j]];
  }
}

// The largest count of acc[0, n) (n > 0).
inline std::uint32_t maxCount(const std::uint32_t* acc, std::size_t n) {
  std::size_t k = 0;
  std::uint32_t best = acc[0];
  if (n >= Ops::kLanes) {
    typename Ops::V m = Ops::load(acc);
    for (k = Ops::kLanes; k + Ops::kLanes <= n; k += Ops::kLanes) m = Ops::max(m, Ops::load(acc + k));
    alignas(32) std::int32_t lanes[Ops::kLanes];
    Ops::store(lanes, m);
    for (const std::int32_t v : lanes) best = std::max(best, static_cast<std::uint32_t>(v));
  }
  for (; k < n; ++k) best = std::max(best, acc[k]);
  return best;
}

// The first k with acc[k] == value (value is in acc[0, n)).
inline std::size_t firstIndexOf(const std::uint32_t* acc, std::size_t n, std::uint32_t value) {
  const typename Ops::V v = Ops::set1(static_cast<std::int32_t>(value));
  std::size_t k = 0;
  for (; k + Ops::kLanes <= n; k += Ops::kLanes) {
    const int hits = Ops::equalMask(Ops::load(acc + k), v);
    if (hits != 0) return k + static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(hits)));
  }
  while (acc[k] != value) ++k;
  return k;
}
