#include "core/connectivity/connectivity.h"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace imagepro {

namespace {

constexpr std::int32_t kNoPixel = -1;

inline bool rasterBefore(const EdgePixel& a, const EdgePixel& b) {
  return a.y != b.y ? a.y < b.y : a.x < b.x;
}

inline bool eightNeighbours(const EdgePixel& a, const EdgePixel& b) {
  return std::abs(a.x - b.x) <= 1 && std::abs(a.y - b.y) <= 1;
}

inline std::size_t indexOffset(const EdgePixel& p, std::size_t stride) {
  return static_cast<std::size_t>(p.y + 1) * stride + static_cast<std::size_t>(p.x + 1);
}

// The eight neighbours in raster order: bit j of a neighbour mask is neighbour j.
using NeighbourOffsets = std::array<std::ptrdiff_t, 8>;

NeighbourOffsets neighbourOffsets(std::ptrdiff_t stride) {
  return {-stride - 1, -stride, -stride + 1, -1, 1, stride - 1, stride, stride + 1};
}

// Bit j set when neighbour j holds an edge pixel not yet in a path: an entry >= 0, i.e.
// with its sign bit clear. The SSE2 form reads the rows above and below as four entries
// each (x - 1 .. x + 2, the spare column keeping the read inside the buffer), packs their
// signs into one byte mask, and reads the centre's row entry by entry: the centre's own
// entry was written as it joined its path a pixel or two before, and a wider read over
// it waits until that write reaches the cache.
inline std::uint32_t freshNeighbours(const std::int32_t* centre, std::ptrdiff_t stride) {
  auto sign = [](std::int32_t entry) { return static_cast<std::uint32_t>(entry) >> 31; };
#if defined(__SSE2__)
  const __m128i above = _mm_loadu_si128(reinterpret_cast<const __m128i*>(centre - stride - 1));
  const __m128i below = _mm_loadu_si128(reinterpret_cast<const __m128i*>(centre + stride - 1));
  const __m128i rows = _mm_packs_epi32(above, below);  // signs survive the saturating packs
  const auto m = static_cast<std::uint32_t>(_mm_movemask_epi8(_mm_packs_epi16(rows, rows)));
  // m: bits 0-3 above, 4-7 below (x + 2 in bits 3 and 7 dropped).
  const std::uint32_t taken = (m & 7U) | (m & 0x70U) << 1 | sign(centre[-1]) << 3 | sign(centre[1]) << 4;
#else
  const NeighbourOffsets offsets = neighbourOffsets(stride);
  std::uint32_t taken = 0;
  for (std::size_t j = 0; j < offsets.size(); ++j) taken |= sign(centre[offsets[j]]) << j;
#endif
  return ~taken & 0xFFU;
}

inline std::uint32_t rasterKey(const EdgePixel& p) {
  return static_cast<std::uint32_t>(static_cast<std::uint16_t>(p.y)) << 16 | static_cast<std::uint16_t>(p.x);
}

void unindex(const EdgeList& edges, std::size_t count, std::int32_t* index, std::size_t stride) {
  for (std::size_t j = 0; j < count; ++j) index[indexOffset(edges[j], stride)] = kNoPixel;
}

// Fast path for lists in strictly increasing raster order, as the edge detectors write
// them: a strictly increasing key y << 16 | x rules out repeats without reading the index
// image, and a column check per pixel plus the last row's check (the first row's too,
// since a negative row is a key above every valid one) keep every pixel inside. Returns
// false, with no entry written, when the list is not of that kind.
bool indexRasterList(const EdgeList& edges, cv::Size imageSize, std::int32_t* index, std::size_t stride) {
  const std::size_t n = edges.size();
  const auto width = static_cast<unsigned>(imageSize.width);
  if (static_cast<unsigned>(edges[n - 1].y) >= static_cast<unsigned>(imageSize.height)) return false;
  const EdgePixel* e = edges.data();
  std::int32_t* origin = index + stride + 1;  // the entry of pixel (0, 0)
  std::size_t i = 0;
  bool ordered = true;
#if defined(__SSE2__)
  // Four pixels per step; the comparisons are signed, so the keys are biased by 2^31.
  // madd of the keys' (x, y) halves with (1, stride) gives the four entries' offsets.
  const __m128i bias = _mm_set1_epi32(INT32_MIN);
  const __m128i one = _mm_set1_epi32(1);
  const __m128i columnAndRow = _mm_set1_epi32(static_cast<std::int32_t>(stride << 16 | 1));
  const __m128i columnBits = _mm_set1_epi32(0xFFFF);
  const __m128i lastColumn = _mm_set1_epi32(imageSize.width - 1);
  // Lane 3: the biased key before the group. INT32_MAX + 1 wraps to the smallest value,
  // so the first pixel follows nothing.
  __m128i previous = _mm_set1_epi32(INT32_MAX);
  alignas(16) std::int32_t offsets[4];
  // madd multiplies 16-bit halves: rows longer than that take the scalar loop.
  const std::size_t whole = stride <= INT16_MAX ? n & ~std::size_t{3} : 0;
  for (; i < whole; i += 4) {
    const __m128 low = _mm_loadu_ps(reinterpret_cast<const float*>(e + i));
    const __m128 high = _mm_loadu_ps(reinterpret_cast<const float*>(e + i + 2));
    const __m128i keys = _mm_castps_si128(_mm_shuffle_ps(low, high, _MM_SHUFFLE(2, 0, 2, 0)));
    const __m128i biased = _mm_xor_si128(keys, bias);
    const __m128i before = _mm_or_si128(_mm_slli_si128(biased, 4), _mm_srli_si128(previous, 12));
    const __m128i notAfter = _mm_cmpgt_epi32(_mm_add_epi32(before, one), biased);
    const __m128i outside = _mm_cmpgt_epi32(_mm_and_si128(keys, columnBits), lastColumn);
    if (_mm_movemask_epi8(_mm_or_si128(notAfter, outside)) != 0) {
      ordered = false;
      break;
    }
    previous = biased;
    _mm_store_si128(reinterpret_cast<__m128i*>(offsets), _mm_madd_epi16(keys, columnAndRow));
    for (std::size_t k = 0; k < 4; ++k) origin[offsets[k]] = static_cast<std::int32_t>(i + k);
  }
#endif
  for (; ordered && i < n; ++i) {
    const std::uint32_t key = rasterKey(e[i]);
    if ((i > 0 && key <= rasterKey(e[i - 1])) || (key & 0xFFFFU) >= width) {
      ordered = false;
      break;
    }
    origin[(key >> 16) * stride + (key & 0xFFFFU)] = static_cast<std::int32_t>(i);
  }
  if (!ordered) unindex(edges, i, index, stride);
  return ordered;
}

// Checks the list against the image and writes each pixel's list index into the index
// image. On failure the entries already written are reset, keeping the "all -1 between
// calls" invariant.
Status indexEdges(const EdgeList& edges, cv::Size imageSize, ConnectivityWorkspace& ws) {
  const int rows = imageSize.height + 2;
  const int cols = imageSize.width + 3;  // a one-pixel frame, plus a spare column for freshNeighbours
  if (ws.index.rows != rows || ws.index.cols != cols || ws.index.type() != CV_32SC1 || !ws.index.isContinuous()) {
    ws.index.create(rows, cols, CV_32SC1);
    ws.index.setTo(kNoPixel);
    const NeighbourOffsets offsets = neighbourOffsets(cols);
    ws.first_neighbour[0] = 0;  // never used: a mask of 0 has no neighbour
    for (std::size_t mask = 1; mask < ws.first_neighbour.size(); ++mask)
      ws.first_neighbour[mask] = offsets[static_cast<std::size_t>(std::countr_zero(mask))];
  }
  std::int32_t* index = ws.index.ptr<std::int32_t>();
  const std::size_t stride = static_cast<std::size_t>(cols);
  if (indexRasterList(edges, imageSize, index, stride)) return Status::Ok;
  // Any other order: a repeat shows as an entry already written.
  // One comparison per coordinate: a negative one wraps far above the image size.
  const auto width = static_cast<unsigned>(imageSize.width), height = static_cast<unsigned>(imageSize.height);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const EdgePixel& p = edges[i];
    const bool inside = static_cast<unsigned>(p.x) < width && static_cast<unsigned>(p.y) < height;
    const std::size_t offset = inside ? indexOffset(p, stride) : 0;
    if (!inside || index[offset] != kNoPixel) {
      unindex(edges, i, index, stride);
      return Status::InvalidEdgeList;
    }
    index[offset] = static_cast<std::int32_t>(i);
  }
  return Status::Ok;
}

// On success `out` has no paths yet but keeps its pixels, which CN1 overwrites (clearing
// them would have them zeroed again on resizing).
Status checkInput(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws) {
  Status s = Status::Ok;
  if (imageSize.width <= 0 || imageSize.height <= 0) {
    s = Status::EmptyFrame;
  } else if (edges.empty()) {
    s = Status::NoEdges;
  } else {
    s = indexEdges(edges, imageSize, ws);
  }
  out.starts.assign(1, 0);
  if (!ok(s)) out.pixels.clear();
  return s;
}

// CN1's walk of one path, breadth first from list entry `first`, appending at `tail`;
// returns the new tail. A pixel's entry goes back to -1 as it joins: it is no longer
// fresh to its neighbours, and the index image is all -1 again when the last path ends,
// with no clearing pass. The queue holds entry addresses, so a step's neighbourhood is
// one load away from the step before it.
std::size_t walkPath(std::size_t first, std::size_t tail, const EdgePixel* __restrict edges,
                     std::int32_t* firstEntry, std::ptrdiff_t stride,
                     const std::ptrdiff_t* __restrict firstNeighbour, EdgePixel* __restrict pixels,
                     std::int32_t** __restrict queue, std::uint8_t* __restrict joined) {
  *firstEntry = kNoPixel;
  joined[first] = 1;
  pixels[tail] = edges[first];
  queue[tail] = firstEntry;
  std::size_t head = tail++;
  do {
    std::int32_t* centre = queue[head];
    // On a contour this is usually one neighbour, so the loop below rarely repeats.
    for (std::uint32_t fresh = freshNeighbours(centre, stride); fresh != 0; fresh &= fresh - 1) {
      std::int32_t* entry = centre + firstNeighbour[fresh];
      const std::int32_t k = *entry;
      joined[k] = 1;
      pixels[tail] = edges[k];
      queue[tail++] = entry;
      *entry = kNoPixel;
    }
  } while (++head < tail);
  return tail;
}

}  // namespace

Status connectCN0(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws) {
  // The index image only validates the list here; the grouping itself does not use it.
  if (const Status s = checkInput(edges, imageSize, out, ws); !ok(s)) return s;
  unindex(edges, edges.size(), ws.index.ptr<std::int32_t>(), static_cast<std::size_t>(ws.index.cols));
  out.pixels.clear();
  out.pixels.reserve(edges.size());

  auto& unassigned = ws.unassigned;
  unassigned.resize(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) unassigned[i] = static_cast<std::uint32_t>(i);
  std::size_t remaining = unassigned.size();

  while (remaining > 0) {
    // The earliest unassigned pixel opens the next path.
    out.pixels.push_back(edges[unassigned[0]]);
    std::copy(unassigned.begin() + 1, unassigned.begin() + static_cast<std::ptrdiff_t>(remaining), unassigned.begin());
    --remaining;
    for (std::size_t head = out.starts.back(); head < out.pixels.size(); ++head) {
      const EdgePixel p = out.pixels[head];
      // Exhaustive scan of the unassigned pixels; they stay in input order.
      std::array<EdgePixel, 8> found;  // no repeated pixels, so at most eight
      std::size_t nFound = 0;
      std::size_t kept = 0;
      for (std::size_t r = 0; r < remaining; ++r) {
        const std::uint32_t k = unassigned[r];
        if (nFound < found.size() && eightNeighbours(edges[k], p)) {
          found[nFound++] = edges[k];
        } else {
          unassigned[kept++] = k;
        }
      }
      remaining = kept;
      // Append in raster order (insertion sort of at most eight), as CN1 visits them.
      for (std::size_t f = 1; f < nFound; ++f)
        for (std::size_t g = f; g > 0 && rasterBefore(found[g], found[g - 1]); --g) std::swap(found[g], found[g - 1]);
      for (std::size_t f = 0; f < nFound; ++f) out.pixels.push_back(found[f]);
    }
    out.starts.push_back(static_cast<std::uint32_t>(out.pixels.size()));
  }
  return Status::Ok;
}

Status connectCN1(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws) {
  if (const Status s = checkInput(edges, imageSize, out, ws); !ok(s)) return s;

  // The reordered list is written straight into `out`; ws.queue holds the index-image
  // entry of each of its pixels, so a pixel's neighbours are found without looking it up
  // again. No allocation once all three have grown.
  const std::size_t n = edges.size();
  out.pixels.resize(n);
  ws.queue.resize(n);
  ws.joined.assign(n + 8, 1);  // 8 past the end: the scan below reads 8 entries at a time
  std::fill_n(ws.joined.begin(), n, std::uint8_t{0});
  ws.joined[n] = 0;  // stops the scan
  std::int32_t* index = ws.index.ptr<std::int32_t>();
  const std::size_t stride = static_cast<std::size_t>(ws.index.cols);
  const std::uint8_t* joined = ws.joined.data();
  std::size_t tail = 0;
  for (std::size_t i = 0;; ++i) {
    // The next list entry not in a path opens the next path: skip 8 joined entries at a
    // time (most entries were taken by earlier paths).
    constexpr std::uint64_t kAllJoined = 0x0101010101010101ULL;
    std::uint64_t eight;
    while (std::memcpy(&eight, joined + i, sizeof eight), eight == kAllJoined) i += 8;
    i += static_cast<std::size_t>(std::countr_zero(~eight & kAllJoined)) / 8;
    if (i >= n) break;
    tail = walkPath(i, tail, edges.data(), index + indexOffset(edges[i], stride), static_cast<std::ptrdiff_t>(stride),
                    ws.first_neighbour.data(), out.pixels.data(), ws.queue.data(), ws.joined.data());
    out.starts.push_back(static_cast<std::uint32_t>(tail));
  }
  return Status::Ok;
}

Status connectPaths(ConnectivityMethod method, const EdgeList& edges, cv::Size imageSize, Paths& out,
                    ConnectivityWorkspace& ws) {
  switch (method) {
    case ConnectivityMethod::CN0: return connectCN0(edges, imageSize, out, ws);
    case ConnectivityMethod::CN1: return connectCN1(edges, imageSize, out, ws);
  }
  out.clear();
  return Status::InvalidSettings;
}

}  // namespace imagepro
