#include "core/edges/edges.h"

#include <algorithm>
#include <bit>
#include <iterator>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace imagepro {

namespace {

constexpr int kMaxSide = 32767;  // EdgePixel stores coordinates as int16

bool usableBinary(const cv::Mat& binary) {
  return !binary.empty() && binary.dims == 2 && binary.type() == CV_8UC1 && binary.cols <= kMaxSide &&
         binary.rows <= kMaxSide;
}

inline int bit(std::uint8_t v) { return v != 0 ? 1 : 0; }

// Sobel responses (eqs. 2.19-2.20) of the 0/1 image at column x, given the pixel's
// row and the rows above and below (already replicated at the image border).
// kInterior: the caller guarantees 0 < x < width - 1, so no column is replicated.
template <bool kInterior = false>
inline EdgePixel sobelPixel(const std::uint8_t* up, const std::uint8_t* cur, const std::uint8_t* down, int x,
                            int y, int width) {
  const int l = kInterior || x > 0 ? x - 1 : 0;
  const int r = kInterior || x < width - 1 ? x + 1 : x;
  const int gx = (bit(up[r]) + 2 * bit(cur[r]) + bit(down[r])) - (bit(up[l]) + 2 * bit(cur[l]) + bit(down[l]));
  const int gy = (bit(down[l]) + 2 * bit(down[x]) + bit(down[r])) - (bit(up[l]) + 2 * bit(up[x]) + bit(up[r]));
  return {static_cast<std::int16_t>(x), static_cast<std::int16_t>(y), static_cast<std::int16_t>(gx),
          static_cast<std::int16_t>(gy)};
}

// Eight pixels at a time. zeroBytes(v) has 0x80 in every byte of v that is zero and 0
// elsewhere; it is exact (no carry crosses a byte), unlike the usual "has zero" test.
constexpr std::uint64_t kLow7 = 0x7F7F7F7F7F7F7F7FULL;
constexpr std::uint64_t kHigh = 0x8080808080808080ULL;
constexpr std::uint64_t kAllWhite = ~std::uint64_t{0};
inline std::uint64_t zeroBytes(std::uint64_t v) { return ~(((v & kLow7) + kLow7) | v) & kHigh; }
inline std::uint64_t load8(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Eq. 2.25 on one row. Rows above/below are the row itself at the image border, and
// the pixel itself stands in for a missing left/right neighbour: a white pixel, so
// never black.
void laplaceRow(const std::uint8_t* up, const std::uint8_t* cur, const std::uint8_t* down, int y, int width,
                EdgeList& out) {
  auto scalar = [&](int x) {
    if (cur[x] == 0) return;
    const int l = x > 0 ? x - 1 : x;
    const int r = x < width - 1 ? x + 1 : x;
    if (up[x] == 0 || down[x] == 0 || cur[l] == 0 || cur[r] == 0) out.push_back(sobelPixel(up, cur, down, x, y, width));
  };
  int x = 0;
  if constexpr (std::endian::native == std::endian::little) {
    // Byte k of a little-endian load is pixel x + k. Whole words need cur[x - 1] and
    // cur[x + 8], so they cover columns 1 .. width - 2; the rest goes pixel by pixel.
    if (width >= 10) {
      scalar(0);
      for (x = 1; x + 9 <= width; x += 8) {
        const std::uint64_t c = load8(cur + x);
        if (c == 0) continue;  // eight black pixels: the common case in a dark scene
        // Eight 255s with 255 above, below and at both ends: inside a white region.
        if (c == kAllWhite && load8(up + x) == kAllWhite && load8(down + x) == kAllWhite && cur[x - 1] != 0 &&
            cur[x + 8] != 0)
          continue;
        std::uint64_t edge = ~zeroBytes(c) & kHigh &
                             (zeroBytes(load8(up + x)) | zeroBytes(load8(down + x)) | zeroBytes(load8(cur + x - 1)) |
                              zeroBytes(load8(cur + x + 1)));
        while (edge != 0) {
          const int k = std::countr_zero(edge) >> 3;
          out.push_back(sobelPixel<true>(up, cur, down, x + k, y, width));
          edge &= edge - 1;
        }
      }
    }
  }
  for (; x < width; ++x) scalar(x);
}

}  // namespace

Status detectEdgesLaplace(const cv::Mat& binary, EdgeList& out) {
  out.clear();
  if (!usableBinary(binary)) return Status::EmptyFrame;
  const int width = binary.cols;
  const int height = binary.rows;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* cur = binary.ptr<std::uint8_t>(y);
    const std::uint8_t* up = y > 0 ? binary.ptr<std::uint8_t>(y - 1) : cur;
    const std::uint8_t* down = y < height - 1 ? binary.ptr<std::uint8_t>(y + 1) : cur;
    laplaceRow(up, cur, down, y, width, out);
  }
  return out.empty() ? Status::NoEdges : Status::Ok;
}

namespace {

// Thinning of thesis 2.4.2 on `mask` (1 = edge, with a zero one-pixel frame so every
// image pixel has eight readable neighbours). Exhaustive: for every edge pixel, every
// pair of its edge neighbours that are themselves neighbours makes a three-pixel
// combination (always three cells of a 2x2 block), and one of the three is deleted;
// the other two stay 8-neighbours. Which one: a black pixel if the triple has one (the
// edge then stays on the white side, where the Laplace edge is), and among the
// candidates the cell 4-adjacent to the other two, else the first in raster order.
// Passes repeat until one deletes nothing.
void thinTriples(const cv::Mat& binary, cv::Mat& mask) {
  static constexpr int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
  static constexpr int kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
  const int width = binary.cols;
  const int height = binary.rows;
  auto isBlack = [&](int x, int y) { return binary.at<std::uint8_t>(y - 1, x - 1) == 0; };  // mask coordinates
  bool changed = true;
  while (changed) {
    changed = false;
    for (int y = 1; y <= height; ++y) {
      for (int x = 1; x <= width; ++x) {
        bool restart = true;
        while (restart && mask.at<std::uint8_t>(y, x) != 0) {
          restart = false;
          for (int i = 0; i < 8 && !restart; ++i) {
            if (mask.at<std::uint8_t>(y + kDy[i], x + kDx[i]) == 0) continue;
            for (int j = i + 1; j < 8; ++j) {
              if (std::abs(kDx[i] - kDx[j]) > 1 || std::abs(kDy[i] - kDy[j]) > 1) continue;
              if (mask.at<std::uint8_t>(y + kDy[j], x + kDx[j]) == 0) continue;
              // The triple in raster order: p's earlier neighbour, p or its later ones.
              cv::Point cells[3] = {{x, y}, {x + kDx[i], y + kDy[i]}, {x + kDx[j], y + kDy[j]}};
              std::sort(std::begin(cells), std::end(cells),
                        [](cv::Point a, cv::Point b) { return a.y != b.y ? a.y < b.y : a.x < b.x; });
              const bool anyBlack = isBlack(cells[0].x, cells[0].y) || isBlack(cells[1].x, cells[1].y) ||
                                    isBlack(cells[2].x, cells[2].y);
              auto candidate = [&](cv::Point c) { return !anyBlack || isBlack(c.x, c.y); };
              auto fourAdjacent = [](cv::Point a, cv::Point b) { return std::abs(a.x - b.x) + std::abs(a.y - b.y) == 1; };
              int victim = -1;
              for (int k = 0; k < 3 && victim < 0; ++k)
                if (candidate(cells[k]) && fourAdjacent(cells[k], cells[(k + 1) % 3]) &&
                    fourAdjacent(cells[k], cells[(k + 2) % 3]))
                  victim = k;
              for (int k = 0; k < 3 && victim < 0; ++k)
                if (candidate(cells[k])) victim = k;
              mask.at<std::uint8_t>(cells[victim].y, cells[victim].x) = 0;
              changed = true;
              restart = true;  // p's neighbourhood changed: search it again
              break;
            }
          }
        }
      }
    }
  }
}

}  // namespace

Status detectEdgesSobelThinning(const cv::Mat& binary, EdgeList& out, EdgeWorkspace& ws) {
  out.clear();
  if (!usableBinary(binary)) return Status::EmptyFrame;
  const int width = binary.cols;
  const int height = binary.rows;
  ws.gx.create(height, width, CV_16SC1);
  ws.gy.create(height, width, CV_16SC1);
  ws.mask.create(height + 2, width + 2, CV_8UC1);
  ws.mask.setTo(0);
  // Eq. 2.21 over the whole image: both sides of every boundary are marked.
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* cur = binary.ptr<std::uint8_t>(y);
    const std::uint8_t* up = y > 0 ? binary.ptr<std::uint8_t>(y - 1) : cur;
    const std::uint8_t* down = y < height - 1 ? binary.ptr<std::uint8_t>(y + 1) : cur;
    auto* gx = ws.gx.ptr<std::int16_t>(y);
    auto* gy = ws.gy.ptr<std::int16_t>(y);
    std::uint8_t* mask = ws.mask.ptr<std::uint8_t>(y + 1) + 1;
    for (int x = 0; x < width; ++x) {
      const EdgePixel p = sobelPixel(up, cur, down, x, y, width);
      gx[x] = p.gx;
      gy[x] = p.gy;
      mask[x] = (p.gx * p.gx + p.gy * p.gy > 0) ? 1 : 0;
    }
  }
  thinTriples(binary, ws.mask);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* mask = ws.mask.ptr<std::uint8_t>(y + 1) + 1;
    const auto* gx = ws.gx.ptr<std::int16_t>(y);
    const auto* gy = ws.gy.ptr<std::int16_t>(y);
    for (int x = 0; x < width; ++x)
      if (mask[x] != 0)
        out.push_back({static_cast<std::int16_t>(x), static_cast<std::int16_t>(y), gx[x], gy[x]});
  }
  return out.empty() ? Status::NoEdges : Status::Ok;
}

Status detectEdges(EdgeMethod method, const cv::Mat& binary, EdgeList& out, EdgeWorkspace& ws) {
  switch (method) {
    case EdgeMethod::SobelThinning: return detectEdgesSobelThinning(binary, out, ws);
    case EdgeMethod::Laplace: return detectEdgesLaplace(binary, out);
  }
  out.clear();
  return Status::InvalidSettings;
}

}  // namespace imagepro
