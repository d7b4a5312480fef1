#include "core/connectivity/connectivity.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdlib>
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

// The 3x3 neighbourhood in raster order: bit 3 * row + column, bit 4 the centre.
using NeighbourOffsets = std::array<std::ptrdiff_t, 9>;

// Bit j set when neighbour j holds an edge pixel not yet in a path: an entry >= 0, i.e.
// with its sign bit clear. The centre, already in a path, is never fresh. The SSE2 form
// reads the rows above and below as four entries each (x - 1 .. x + 2), which the index
// image's spare column keeps inside the buffer, and the centre's row entry by entry: the
// centre's own entry was written as it joined its path a pixel or two before, and a
// wider read over it waits until that write reaches the cache (8-18 % of the time).
inline std::uint32_t freshNeighbours(const std::int32_t* centre, const NeighbourOffsets& offsets) {
#if defined(__SSE2__)
  auto signs = [](const std::int32_t* p) {
    return static_cast<std::uint32_t>(_mm_movemask_ps(_mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)))));
  };
  auto sign = [](std::int32_t entry) { return static_cast<std::uint32_t>(entry) >> 31; };
  const std::uint32_t taken = (signs(centre + offsets[0]) & 7U) | sign(centre[-1]) << 3 | 1U << 4 |
                              sign(centre[1]) << 5 | (signs(centre + offsets[6]) & 7U) << 6;
  return ~taken & 0x1FFU;
#else
  std::uint32_t fresh = 0;
  for (std::size_t j = 0; j < offsets.size(); ++j)
    fresh |= ((static_cast<std::uint32_t>(centre[offsets[j]]) >> 31) ^ 1U) << j;
  return fresh;
#endif
}

void startPaths(const EdgeList& edges, Paths& out) {
  out.clear();
  out.pixels.reserve(edges.size());
}

// Checks the list against the image, writes each pixel's list index into the index
// image and its position there into ws.offsets. On failure the entries already
// written are reset, keeping the "all -1 between calls" invariant.
Status indexEdges(const EdgeList& edges, cv::Size imageSize, ConnectivityWorkspace& ws) {
  const int rows = imageSize.height + 2;
  const int cols = imageSize.width + 3;  // a one-pixel frame, plus a spare column for freshNeighbours
  if (ws.index.rows != rows || ws.index.cols != cols || ws.index.type() != CV_32SC1 || !ws.index.isContinuous()) {
    ws.index.create(rows, cols, CV_32SC1);
    ws.index.setTo(kNoPixel);
  }
  std::int32_t* index = ws.index.ptr<std::int32_t>();
  const std::size_t stride = static_cast<std::size_t>(cols);
  ws.offsets.resize(edges.size());
  // One comparison per coordinate: a negative one wraps far above the image size.
  const auto width = static_cast<unsigned>(imageSize.width), height = static_cast<unsigned>(imageSize.height);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const EdgePixel& p = edges[i];
    const bool inside = static_cast<unsigned>(p.x) < width && static_cast<unsigned>(p.y) < height;
    const std::size_t offset = inside ? indexOffset(p, stride) : 0;
    if (!inside || index[offset] != kNoPixel) {
      for (std::size_t j = 0; j < i; ++j) index[ws.offsets[j]] = kNoPixel;
      return Status::InvalidEdgeList;
    }
    index[offset] = static_cast<std::int32_t>(i);
    ws.offsets[i] = static_cast<std::uint32_t>(offset);
  }
  return Status::Ok;
}

void clearIndex(ConnectivityWorkspace& ws) {
  std::int32_t* index = ws.index.ptr<std::int32_t>();
  for (const std::uint32_t offset : ws.offsets) index[offset] = kNoPixel;
}

Status checkInput(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws) {
  out.clear();
  if (imageSize.width <= 0 || imageSize.height <= 0) return Status::EmptyFrame;
  if (edges.empty()) return Status::NoEdges;
  return indexEdges(edges, imageSize, ws);
}

}  // namespace

Status connectCN0(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws) {
  // The index image only validates the list here; the grouping itself does not use it.
  if (const Status s = checkInput(edges, imageSize, out, ws); !ok(s)) return s;
  clearIndex(ws);
  startPaths(edges, out);

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
  startPaths(edges, out);

  std::int32_t* index = ws.index.ptr<std::int32_t>();
  const std::ptrdiff_t s = ws.index.cols;
  // The index image's one-pixel frame of -1 makes the neighbours readable at the image
  // border.
  const NeighbourOffsets neighbourOffsets = {-s - 1, -s, -s + 1, -1, 0, 1, s - 1, s, s + 1};

  // The reordered list is written straight into `out`; ws.order holds the index-image
  // position of each of its pixels, so a pixel's neighbours are found without looking
  // it up again. No allocation once both have grown.
  const std::size_t n = edges.size();
  const std::uint32_t* offsets = ws.offsets.data();
  out.pixels.resize(n);
  ws.order.resize(n);
  EdgePixel* pixels = out.pixels.data();
  std::uint32_t* queue = ws.order.data();
  std::size_t tail = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (index[offsets[i]] == kNoPixel) continue;  // already in a path
    // A pixel put in a path goes back to -1 at once: not fresh to its neighbours, and
    // the index image is all -1 again when the last path ends, with no clearing pass.
    index[offsets[i]] = kNoPixel;
    pixels[tail] = edges[i];
    queue[tail++] = offsets[i];
    // The path grows at the list's end while `head` walks it.
    for (std::size_t head = out.starts.back(); head < tail; ++head) {
      const std::ptrdiff_t centre = queue[head];
      // On a contour this is usually one neighbour, so the loop below rarely repeats.
      std::uint32_t fresh = freshNeighbours(index + centre, neighbourOffsets);
      while (fresh != 0) {
        const std::ptrdiff_t at = centre + neighbourOffsets[static_cast<std::size_t>(std::countr_zero(fresh))];
        fresh &= fresh - 1;
        pixels[tail] = edges[static_cast<std::size_t>(index[at])];
        queue[tail++] = static_cast<std::uint32_t>(at);
        index[at] = kNoPixel;
      }
    }
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
