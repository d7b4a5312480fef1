#include "core/edges/edges.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <iterator>

#if defined(__SSE2__)
#include <emmintrin.h>
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

// Sixteen pixels at a time: load16 reads p[0] .. p[15], darker is the bytewise
// minimum, and bit k of blackMask is set when byte k is black (zero).
#if defined(__SSE2__)
using Pixels16 = __m128i;
inline Pixels16 load16(const std::uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
inline Pixels16 darker(Pixels16 a, Pixels16 b) { return _mm_min_epu8(a, b); }
inline unsigned blackMask(Pixels16 v) {
  return static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128())));
}
#else
using Pixels16 = std::array<std::uint8_t, 16>;
inline Pixels16 load16(const std::uint8_t* p) {
  Pixels16 v;
  std::copy_n(p, v.size(), v.begin());
  return v;
}
inline Pixels16 darker(Pixels16 a, const Pixels16& b) {
  for (std::size_t k = 0; k < a.size(); ++k) a[k] = std::min(a[k], b[k]);
  return a;
}
inline unsigned blackMask(const Pixels16& v) {
  unsigned mask = 0;
  for (std::size_t k = 0; k < v.size(); ++k) mask |= static_cast<unsigned>(v[k] == 0) << k;
  return mask;
}
#endif

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

// Eq. 2.25 on the sixteen pixels x .. x + 15 of a row (1 <= x, x + 16 < width), those
// of `keep` only. A block of black pixels, the common case in a dark scene, costs one
// load; any other block six loads.
inline void laplaceBlock(const std::uint8_t* up, const std::uint8_t* cur, const std::uint8_t* down, int x, int y,
                         unsigned keep, EdgeList& out) {
  const unsigned black = blackMask(load16(cur + x));
  if ((~black & keep) == 0) return;
  const Pixels16 left = load16(cur + x - 1), right = load16(cur + x + 1);
  // A black 4-neighbour makes the darkest of the four black.
  const unsigned blackNeighbour =
      blackMask(darker(darker(load16(up + x), load16(down + x)), darker(left, right)));
  unsigned edge = ~black & keep & blackNeighbour;
  if (edge == 0) return;
  // The black pixels of the three rows over x - 1 .. x + 16 in three 21-bit fields:
  // shifted right by k, each field's low three bits are the neighbourhood of pixel x + k.
  auto row18 = [](const Pixels16& l, const Pixels16& r) { return std::uint64_t{blackMask(l) | blackMask(r) << 2}; };
  const std::uint64_t rows = row18(load16(up + x - 1), load16(up + x + 1)) | row18(left, right) << 21 |
                             row18(load16(down + x - 1), load16(down + x + 1)) << 42;
  const std::uint64_t row = bitsOf(EdgePixel{0, static_cast<std::int16_t>(y), 0, 0});
  while (edge != 0) {
    const int k = std::countr_zero(edge);
    edge &= edge - 1;
    const std::uint64_t w = rows >> k;
    const std::uint64_t gradient = kSobelByBlackNeighbourhood[(w & 0x7U) | (w >> 18 & 0x38U) | (w >> 36 & 0x1C0U)];
    out.push_back(std::bit_cast<EdgePixel>(gradient | row | bitsOf(EdgePixel{static_cast<std::int16_t>(x + k), 0, 0, 0})));
  }
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
  constexpr int kBlock = 16;
  // Blocks read cur[x - 1] .. cur[x + 16], so they cover columns 1 .. width - 2; the
  // last one overlaps its predecessor and keeps only the columns not yet done.
  if (width < kBlock + 2) {
    for (int x = 0; x < width; ++x) scalar(x);
    return;
  }
  scalar(0);
  const int last = width - 1 - kBlock;
  int x = 1;
  for (; x <= last; x += kBlock) laplaceBlock(up, cur, down, x, y, 0xFFFFU, out);
  if (x < width - 1) laplaceBlock(up, cur, down, last, y, 0xFFFFU << (x - last) & 0xFFFFU, out);
  scalar(width - 1);
}

}  // namespace

Status detectEdgesLaplace(const cv::Mat& binary, EdgeList& out) {
  out.clear();
  if (!usableBinary(binary)) return Status::EmptyFrame;
  const int width = binary.cols;
  const int height = binary.rows;
  const std::size_t step = binary.step;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* cur = binary.data + step * static_cast<std::size_t>(y);
    const std::uint8_t* up = y > 0 ? cur - step : cur;
    const std::uint8_t* down = y < height - 1 ? cur + step : cur;
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
