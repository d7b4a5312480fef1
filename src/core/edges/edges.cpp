#include "core/edges/edges.h"

#include "core/common/simd_level.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <iterator>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

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
inline EdgePixel sobelPixel(const std::uint8_t* up, const std::uint8_t* cur, const std::uint8_t* down, int x,
                            int y, int width) {
  const int l = x > 0 ? x - 1 : 0;
  const int r = x < width - 1 ? x + 1 : x;
  const int gx = (bit(up[r]) + 2 * bit(cur[r]) + bit(down[r])) - (bit(up[l]) + 2 * bit(cur[l]) + bit(down[l]));
  const int gy = (bit(down[l]) + 2 * bit(down[x]) + bit(down[r])) - (bit(up[l]) + 2 * bit(up[x]) + bit(up[r]));
  return {static_cast<std::int16_t>(x), static_cast<std::int16_t>(y), static_cast<std::int16_t>(gx),
          static_cast<std::int16_t>(gy)};
}

// An edge pixel as its eight bytes, so it is put together with two ORs: the fields
// never share a byte, whatever the byte order.
constexpr std::uint64_t bitsOf(const EdgePixel& p) { return std::bit_cast<std::uint64_t>(p); }

// The Sobel responses (eqs. 2.19-2.20) of a 3x3 neighbourhood of the 0/1 image,
// indexed by its black pixels: bit 3 * row + column, rows up, centre, down and
// columns left, centre, right. Held as edge pixels at (0, 0).
constexpr std::array<std::uint64_t, 512> kSobelByBlackNeighbourhood = [] {
  std::array<std::uint64_t, 512> table{};
  for (int i = 0; i < 512; ++i) {
    auto w = [i](int row, int col) { return ((i >> (3 * row + col)) & 1) != 0 ? 0 : 1; };
    const auto gx = static_cast<std::int16_t>((w(0, 2) + 2 * w(1, 2) + w(2, 2)) - (w(0, 0) + 2 * w(1, 0) + w(2, 0)));
    const auto gy = static_cast<std::int16_t>((w(2, 0) + 2 * w(2, 1) + w(2, 2)) - (w(0, 0) + 2 * w(0, 1) + w(0, 2)));
    table[static_cast<std::size_t>(i)] = bitsOf(EdgePixel{0, 0, gx, gy});
  }
  return table;
}();

// Eq. 2.25 on pixel x of a row. Rows above/below are the row itself at the image
// border, and the pixel itself stands in for a missing left/right neighbour: a white
// pixel, so never black.
inline void laplacePixel(const std::uint8_t* up, const std::uint8_t* cur, const std::uint8_t* down, int x, int y,
                         int width, EdgeList& out) {
  if (cur[x] == 0) return;
  const int l = x > 0 ? x - 1 : x;
  const int r = x < width - 1 ? x + 1 : x;
  if (up[x] == 0 || down[x] == 0 || cur[l] == 0 || cur[r] == 0) out.push_back(sobelPixel(up, cur, down, x, y, width));
}

#if defined(__SSE2__)
namespace sse2 {
#include "core/edges/laplace_rows.inc"
}  // namespace sse2

#if defined(__GNUC__) && !defined(__clang__)
#define LAPLACE_AVX2 1
#pragma GCC push_options
#pragma GCC target("avx2,bmi,bmi2")
namespace avx2 {
#include "core/edges/laplace_rows.inc"
}  // namespace avx2
#pragma GCC pop_options
#undef LAPLACE_AVX2

bool hasAvx2() { return simdLevel() == SimdLevel::Avx2; }
#else
// Other compilers (clang: the fuzz build) take the SSE2 rows.
namespace avx2 {
using sse2::laplaceRows;
}  // namespace avx2
bool hasAvx2() { return false; }
#endif
#endif

}  // namespace

Status detectEdgesLaplace(const cv::Mat& binary, EdgeList& out) {
  out.clear();
  if (!usableBinary(binary)) return Status::EmptyFrame;
#if defined(__SSE2__)
  if (hasAvx2())
    avx2::laplaceRows(binary, out);
  else
    sse2::laplaceRows(binary, out);
#else
  for (int y = 0; y < binary.rows; ++y) {
    const std::uint8_t* cur = binary.ptr<std::uint8_t>(y);
    const std::uint8_t* up = y > 0 ? binary.ptr<std::uint8_t>(y - 1) : cur;
    const std::uint8_t* down = y < binary.rows - 1 ? binary.ptr<std::uint8_t>(y + 1) : cur;
    for (int x = 0; x < binary.cols; ++x) laplacePixel(up, cur, down, x, y, binary.cols, out);
  }
#endif
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
