#include "core/connectivity/connectivity.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <utility>

namespace imagepro {

namespace {

constexpr std::int32_t kNoPixel = -1;
constexpr std::int32_t kAssigned = -2;

inline bool rasterBefore(const EdgePixel& a, const EdgePixel& b) {
  return a.y != b.y ? a.y < b.y : a.x < b.x;
}

inline bool eightNeighbours(const EdgePixel& a, const EdgePixel& b) {
  return std::abs(a.x - b.x) <= 1 && std::abs(a.y - b.y) <= 1;
}

inline std::size_t indexOffset(const EdgePixel& p, std::size_t stride) {
  return static_cast<std::size_t>(p.y + 1) * stride + static_cast<std::size_t>(p.x + 1);
}

void startPaths(const EdgeList& edges, Paths& out) {
  out.clear();
  out.pixels.reserve(edges.size());
}

// Checks the list against the image and writes each pixel's list index into the
// index image. On failure the entries already written are reset, keeping the
// "all -1 between calls" invariant.
Status indexEdges(const EdgeList& edges, cv::Size imageSize, ConnectivityWorkspace& ws) {
  const int rows = imageSize.height + 2;
  const int cols = imageSize.width + 2;
  if (ws.index.rows != rows || ws.index.cols != cols || ws.index.type() != CV_32SC1 || !ws.index.isContinuous()) {
    ws.index.create(rows, cols, CV_32SC1);
    ws.index.setTo(kNoPixel);
  }
  std::int32_t* index = ws.index.ptr<std::int32_t>();
  const std::size_t stride = static_cast<std::size_t>(cols);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const EdgePixel& p = edges[i];
    const bool inside = p.x >= 0 && p.y >= 0 && p.x < imageSize.width && p.y < imageSize.height;
    if (!inside || index[indexOffset(p, stride)] != kNoPixel) {
      for (std::size_t j = 0; j < i; ++j) index[indexOffset(edges[j], stride)] = kNoPixel;
      return Status::InvalidEdgeList;
    }
    index[indexOffset(p, stride)] = static_cast<std::int32_t>(i);
  }
  return Status::Ok;
}

void clearIndex(const EdgeList& edges, ConnectivityWorkspace& ws) {
  std::int32_t* index = ws.index.ptr<std::int32_t>();
  const std::size_t stride = static_cast<std::size_t>(ws.index.cols);
  for (const EdgePixel& p : edges) index[indexOffset(p, stride)] = kNoPixel;
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
  clearIndex(edges, ws);
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
  const std::size_t stride = static_cast<std::size_t>(ws.index.cols);
  const std::ptrdiff_t s = static_cast<std::ptrdiff_t>(stride);
  // The eight neighbours in raster order; the index image's one-pixel frame of -1
  // makes them readable at the image border.
  const std::array<std::ptrdiff_t, 8> neighbourOffsets = {-s - 1, -s, -s + 1, -1, 1, s - 1, s, s + 1};

  for (const EdgePixel& seed : edges) {
    std::int32_t* seedEntry = index + indexOffset(seed, stride);
    if (*seedEntry == kAssigned) continue;
    *seedEntry = kAssigned;
    out.pixels.push_back(seed);
    // out.pixels is the reordered list: the path grows at its end while `head` walks it.
    for (std::size_t head = out.starts.back(); head < out.pixels.size(); ++head) {
      std::int32_t* centre = index + indexOffset(out.pixels[head], stride);
      for (const std::ptrdiff_t d : neighbourOffsets) {
        const std::int32_t k = centre[d];
        if (k < 0) continue;  // no edge pixel there, or already in a path
        centre[d] = kAssigned;
        out.pixels.push_back(edges[static_cast<std::size_t>(k)]);
      }
    }
    out.starts.push_back(static_cast<std::uint32_t>(out.pixels.size()));
  }
  clearIndex(edges, ws);
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
