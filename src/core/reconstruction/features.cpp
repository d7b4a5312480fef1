#include "core/reconstruction/features.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "core/common/simd_level.h"
#include "core/reconstruction/spot_model.h"

#include "core/segmentation/image_buffer.h"
#include "core/segmentation/threshold.h"

namespace imagepro {

namespace {

constexpr double kSpotSearchScale = 0.85;  // spots are searched inside 0.85 of the rim
constexpr int kSpotBoxGrowPx = 3;
constexpr double kSpotRimClearancePx = 2.5;  // spot centroids ignore pixels this near the rim
constexpr double kRaySteps = 16.0;  // 8 points MOD: samples per pixel along a ray
constexpr double kMinSubPixelContrastFraction = 0.3;
constexpr double kSubPixelPoints = 160.0;

// The detected ellipse as a quadratic form: rho^2 = P dx^2 + 2 Q dx dy + R dy^2 with
// (dx, dy) from its centre; rho = 1 on the ellipse.
struct EllipseForm {
  double cx = 0, cy = 0, P = 0, Q = 0, R = 0;

  EllipseForm(const Ellipse& e, double scale) : cx(e.cx), cy(e.cy) {
    const double t = e.angle_deg * M_PI / 180.0;
    const double c = std::cos(t), s = std::sin(t);
    const double ia2 = 1.0 / (scale * scale * e.a * e.a), ib2 = 1.0 / (scale * scale * e.b * e.b);
    P = c * c * ia2 + s * s * ib2;
    Q = c * s * (ia2 - ib2);
    R = s * s * ia2 + c * c * ib2;
  }
  double rho2(double x, double y) const {
    const double dx = x - cx, dy = y - cy;
    return P * dx * dx + 2.0 * Q * dx * dy + R * dy * dy;
  }
  // Radius of curvature of the level curve through (x, y): |grad|^3 / |t^T H |grad|^2 t|.
  double curvatureRadius(double x, double y) const {
    const double dx = x - cx, dy = y - cy;
    const double gx = P * dx + Q * dy, gy = Q * dx + R * dy;  // half the gradient
    const double tHt = P * gy * gy - 2.0 * Q * gx * gy + R * gx * gx;  // tangent (-gy, gx)
    const double g2 = gx * gx + gy * gy;
    return std::abs(tHt) > 0.0 ? g2 * std::sqrt(g2) / std::abs(tHt) : INFINITY;
  }
  // The ellipse's crossings of row y (false when it misses the row).
  bool rowCrossings(double y, double& xLeft, double& xRight) const {
    const double dy = y - cy;
    const double disc = Q * Q * dy * dy - P * (R * dy * dy - 1.0);
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    xLeft = cx + (-Q * dy - root) / P;
    xRight = cx + (-Q * dy + root) / P;
    return true;
  }
  bool columnCrossings(double x, double& yTop, double& yBottom) const {
    const double dx = x - cx;
    const double disc = Q * Q * dx * dx - R * (P * dx * dx - 1.0);
    if (disc < 0.0) return false;
    const double root = std::sqrt(disc);
    yTop = cy + (-Q * dx - root) / R;
    yBottom = cy + (-Q * dx + root) / R;
    return true;
  }
  // Is the rim at (x, y) closer to vertical (its normal closer to the u axis)?
  bool normalMostlyHorizontal(double x, double y) const {
    const double dx = x - cx, dy = y - cy;
    return std::abs(P * dx + Q * dy) >= std::abs(Q * dx + R * dy);
  }
  // Distance along unit direction (ux, uy) from the centre to the ellipse.
  double rayLength(double ux, double uy) const {
    return 1.0 / std::sqrt(P * ux * ux + 2.0 * Q * ux * uy + R * uy * uy);
  }
};

// floor() and round() to int without a call into libm (hot loops; finite pixel coordinates).
int floorToInt(double v) {
  const int i = static_cast<int>(v);
  return i - (v < i ? 1 : 0);
}
int ceilToInt(double v) { return -floorToInt(-v); }
int roundToInt(double v) { return floorToInt(v + 0.5); }

// Eq. 2.1 over a crop, as binarize() does it (255 where grey > t), in a plain loop the
// compiler vectorises: on a crop of a few thousand pixels cv::threshold's set-up costs
// more than the work. `out` keeps an allocation the size of the whole frame.
void binarizeCrop(const cv::Mat& grey, const cv::Rect& crop, int t, cv::Mat& out) {
  reuseBuffer(out, crop.size(), grey.size());
  if (t < 0 || t >= 255) {
    out.setTo(t < 0 ? 255 : 0);
    return;
  }
  const auto level = static_cast<std::uint8_t>(t);
  // Blocks of a fixed size through local arrays: no aliasing, a known trip count, so -O2
  // turns each block into a few vector instructions.
  constexpr int kBlock = 16;
  std::array<std::uint8_t, kBlock> a{}, b{};
  for (int y = 0; y < crop.height; ++y) {
    const std::uint8_t* in = grey.ptr<std::uint8_t>(crop.y + y) + crop.x;
    std::uint8_t* o = out.ptr<std::uint8_t>(y);
    int x = 0;
    for (; x + kBlock <= crop.width; x += kBlock) {
      std::memcpy(a.data(), in + x, kBlock);
      for (int i = 0; i < kBlock; ++i) b[i] = a[i] > level ? 255 : 0;
      std::memcpy(o + x, b.data(), kBlock);
    }
    for (; x < crop.width; ++x) o[x] = in[x] > level ? 255 : 0;
  }
}

// The spot search's row scan (dark_runs_pass.h), once per vector width: the widest the
// processor has is taken at run time (core/common/simd_level.h); every width finds the
// same runs.
#if defined(__SSE2__)
namespace sse2 {
struct Ops {
  static constexpr int kBlock = 16;
  using Level = __m128i;
  using Block = __m128i;
  static Level level(std::uint8_t cut) { return _mm_set1_epi8(static_cast<char>(cut)); }
  static std::uint8_t value(const Level& l) { return static_cast<std::uint8_t>(_mm_cvtsi128_si32(l)); }
  static Block load(const std::uint8_t* p) { return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p)); }
  static Block min(const Block& a, const Block& b) { return _mm_min_epu8(a, b); }
  // g <= level exactly when min(g, level) == g.
  static unsigned dark(const Block& g, const Level& l) {
    return static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_min_epu8(g, l), g)));
  }
  static unsigned darkMask(const std::uint8_t* p, const Level& l) { return dark(load(p), l); }
};
#include "core/reconstruction/dark_runs_pass.h"
}  // namespace sse2

#pragma GCC push_options
#pragma GCC target("avx2")
namespace avx2 {
struct Ops {
  static constexpr int kBlock = 32;
  using Level = __m256i;
  using Block = __m256i;
  static Level level(std::uint8_t cut) { return _mm256_set1_epi8(static_cast<char>(cut)); }
  static std::uint8_t value(const Level& l) {
    return static_cast<std::uint8_t>(_mm_cvtsi128_si32(_mm256_castsi256_si128(l)));
  }
  static Block load(const std::uint8_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
  static Block min(const Block& a, const Block& b) { return _mm256_min_epu8(a, b); }
  static unsigned dark(const Block& g, const Level& l) {
    return static_cast<unsigned>(_mm256_movemask_epi8(_mm256_cmpeq_epi8(_mm256_min_epu8(g, l), g)));
  }
  static unsigned darkMask(const std::uint8_t* p, const Level& l) { return dark(load(p), l); }
};
#include "core/reconstruction/dark_runs_pass.h"
}  // namespace avx2
#pragma GCC pop_options
#else
namespace scalar {
struct Ops {
  static constexpr int kBlock = 16;
  using Level = std::uint8_t;
  using Block = std::array<std::uint8_t, kBlock>;
  static Level level(std::uint8_t cut) { return cut; }
  static std::uint8_t value(Level l) { return l; }
  static Block load(const std::uint8_t* p) {
    Block b;
    std::memcpy(b.data(), p, kBlock);
    return b;
  }
  static Block min(const Block& a, const Block& b) {
    Block m;
    for (int i = 0; i < kBlock; ++i) m[i] = std::min(a[i], b[i]);
    return m;
  }
  static unsigned dark(const Block& g, Level l) {
    unsigned mask = 0;
    for (int i = 0; i < kBlock; ++i) mask |= (g[i] <= l ? 1u : 0u) << i;
    return mask;
  }
  static unsigned darkMask(const std::uint8_t* p, Level l) { return dark(load(p), l); }
};
#include "core/reconstruction/dark_runs_pass.h"
}  // namespace scalar
#endif

struct DarkRowScan {
  int (*runs)(const std::uint8_t*, int, int, std::uint8_t, int, int*);
  bool (*any)(const std::uint8_t* const*, int, int, int, std::uint8_t, int);
};

DarkRowScan darkRowScanForThisProcessor() {
#if defined(__SSE2__)
  if (simdLevel() == SimdLevel::Avx2) return {&avx2::darkRuns, &avx2::anyDark};
  return {&sse2::darkRuns, &sse2::anyDark};
#else
  return {&scalar::darkRuns, &scalar::anyDark};
#endif
}

// Sums of g and of i g over the n pixels g = p[i]. With SSE2 sixteen pixels per step, g
// summed by _mm_sad_epu8 and i g by _mm_madd_epi16, in blocks of kMomentBlock pixels: i
// then fits an int16 lane and a block's i g (below 255 * 2048^2 / 2) an int32.
void rowMoments(const std::uint8_t* p, int n, std::int64_t& sumG, std::int64_t& sumIG) {
  constexpr int kMomentBlock = 2048;
  std::int64_t g = 0, ig = 0;
  int i = 0;
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128(), eight = _mm_set1_epi16(8), sixteen = _mm_set1_epi16(16);
  for (int start = 0; start + 16 <= n; start += kMomentBlock) {
    const int end = std::min(n, start + kMomentBlock);
    __m128i index = _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7);  // i - start
    __m128i sums = zero, moments = zero;
    for (i = start; i + 16 <= end; i += 16) {
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i));
      sums = _mm_add_epi64(sums, _mm_sad_epu8(v, zero));
      moments = _mm_add_epi32(moments, _mm_madd_epi16(_mm_unpacklo_epi8(v, zero), index));
      moments = _mm_add_epi32(moments, _mm_madd_epi16(_mm_unpackhi_epi8(v, zero), _mm_add_epi16(index, eight)));
      index = _mm_add_epi16(index, sixteen);
    }
    std::array<std::int64_t, 2> s{};
    std::array<std::int32_t, 4> m{};
    _mm_storeu_si128(reinterpret_cast<__m128i*>(s.data()), sums);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(m.data()), moments);
    const std::int64_t block_g = s[0] + s[1];
    g += block_g;
    ig += static_cast<std::int64_t>(m[0]) + m[1] + m[2] + m[3] + static_cast<std::int64_t>(start) * block_g;
    if (i < end) break;  // a tail of fewer than 16 pixels: taken below
  }
  if (i < n && n >= 16) {
    // The tail as the last 16 pixels of the row, those before i masked off: lane l is
    // pixel at + l, so i g = l g + at g.
    const int at = n - 16;
    const __m128i lanes = _mm_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m128i keep = _mm_cmpgt_epi8(lanes, _mm_set1_epi8(static_cast<char>(i - at - 1)));
    const __m128i v = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + at)), keep);
    const __m128i sums = _mm_sad_epu8(v, zero);
    const __m128i moments =
        _mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi8(v, zero), _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7)),
                      _mm_madd_epi16(_mm_unpackhi_epi8(v, zero), _mm_setr_epi16(8, 9, 10, 11, 12, 13, 14, 15)));
    std::array<std::int64_t, 2> s{};
    std::array<std::int32_t, 4> m{};
    _mm_storeu_si128(reinterpret_cast<__m128i*>(s.data()), sums);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(m.data()), moments);
    const std::int64_t tail_g = s[0] + s[1];
    g += tail_g;
    ig += static_cast<std::int64_t>(m[0]) + m[1] + m[2] + m[3] + static_cast<std::int64_t>(at) * tail_g;
    i = n;
  }
#endif
  for (; i < n; ++i) {
    g += p[i];
    ig += static_cast<std::int64_t>(i) * p[i];
  }
  sumG = g;
  sumIG = ig;
}

// One image row or column of 8-bit pixels, indexed by its image coordinate k in
// [first, last]: the grey frame's whole line, or the binary crop's part of it.
struct PixelLine {
  const std::uint8_t* data = nullptr;  // the pixel at `first`
  std::ptrdiff_t stride = 1;
  int first = 0, last = -1;

  static PixelLine row(const cv::Mat& m, int y, int x0 = 0) {
    return {m.ptr<std::uint8_t>(y), 1, x0, x0 + m.cols - 1};
  }
  static PixelLine column(const cv::Mat& m, int x, int y0 = 0) {
    return {m.ptr<std::uint8_t>(0) + x, static_cast<std::ptrdiff_t>(m.step[0]), y0, y0 + m.rows - 1};
  }
  bool contains(int k) const { return k >= first && k <= last; }
  double at(int k) const { return data[(k - first) * stride]; }
  bool above(int k, int level) const { return contains(k) && data[(k - first) * stride] > level; }
  bool interp(double x, double& value) const {
    const int k = floorToInt(x);
    if (k < first || k + 1 > last) return false;
    const double f = x - k;
    value = (1.0 - f) * at(k) + f * at(k + 1);
    return true;
  }
};

// The binary crop seen in image coordinates; outside the crop counts as black.
struct BinaryView {
  const cv::Mat& binary;
  cv::Rect crop;
  bool white(int x, int y) const {
    const int cx = x - crop.x, cy = y - crop.y;
    if (cx < 0 || cy < 0 || cx >= crop.width || cy >= crop.height) return false;
    return binary.ptr<std::uint8_t>(cy)[cx] != 0;
  }
};

// Rows and columns of an image covering `area` (image coordinates), white above `level`:
// the binary crop (level 0) or the grey frame at the threshold.
struct ThresholdLines {
  const cv::Mat& image;
  cv::Rect area;
  int level;
  PixelLine row(int y) const {
    return y >= area.y && y < area.y + area.height ? PixelLine::row(image, y - area.y, area.x) : PixelLine{};
  }
  PixelLine column(int x) const {
    return x >= area.x && x < area.x + area.width ? PixelLine::column(image, x - area.x, area.y) : PixelLine{};
  }
};

// The crop's two grey classes (its mean dark and bright levels).
struct EdgeLevels {
  double dark = 0.0, bright = 255.0;
  double contrast() const { return bright - dark; }
  // An edge must rise by a fair part of the crop's contrast to be refined.
  double minContrast() const { return kMinSubPixelContrastFraction * std::max(contrast(), 1.0); }
};

// The edge's position from the area under the profile: over pixels a..b straddling the edge,
// each pixel's grey level, scaled between the two plateaus, is the white fraction of its
// length, so the white run's length fixes the edge. Exact for a straight edge under any
// blur that keeps the grey sum (a pixel's area average, a symmetric point spread), where the
// linear interpolation between two pixels errs by up to 0.1-0.2 px on a sharp edge.
// `roomPx` is the smaller of the line's run inside the rim and the rim's radius of
// curvature there: on a target seen very obliquely the window would hold the far rim or a
// strongly curved edge, and the linear crossing is kept.
constexpr int kAreaHalfWindow = 4;  // pixels either side of the crossing
constexpr double kAreaRoomPx = 3 * (kAreaHalfWindow + 2);  // the least room the area estimate needs

bool areaCrossing(const PixelLine& line, int in, const EdgeLevels& levels, double roomPx, double& x0) {
  constexpr int kHalfWindow = kAreaHalfWindow;
  constexpr double kPlateauTolerance = 0.15;  // of the contrast: the window's ends are on the plateaus
  constexpr double kClassTolerance = 0.3;     // of the crop's contrast: plateaus near its class means
  if (roomPx < kAreaRoomPx) return false;
  const int c = roundToInt(x0);
  if (!line.contains(c - kHalfWindow - 2) || !line.contains(c + kHalfWindow + 2)) return false;
  // px(j): the pixel j steps inwards from c, whichever way the line runs.
  const std::uint8_t* centre = line.data + (c - line.first) * line.stride;
  const std::ptrdiff_t inwards = in * line.stride;
  auto px = [&](int j) { return int{centre[j * inwards]}; };
  // Plateaus just beyond the window, as sums of their two pixels (integers, so the tests on
  // the mid-level below are exact).
  const int outside2 = px(-kHalfWindow - 1) + px(-kHalfWindow - 2);
  const int inside2 = px(kHalfWindow + 1) + px(kHalfWindow + 2);
  const double outside = 0.5 * outside2, inside = 0.5 * inside2;
  const double contrast = inside - outside;
  if (!(contrast >= levels.minContrast())) return false;
  // The plateaus must be the rim's own white and the card's black, not the scene beyond a
  // card seen edge-on.
  const double classTolerance = kClassTolerance * levels.contrast();
  if (std::abs(outside - levels.dark) > classTolerance || std::abs(inside - levels.bright) > classTolerance)
    return false;
  const double plateauTolerance = kPlateauTolerance * contrast;
  if (std::abs(px(-kHalfWindow) - outside) > plateauTolerance || std::abs(px(kHalfWindow) - inside) > plateauTolerance)
    return false;
  // One clean edge: white more than 1.5 px on its inner side, black more than 1.5 px on its
  // outer side, nothing else (a spot, or the far rim of a target seen obliquely) in the window.
  // x0 lies u inwards of c with |u| <= 1/2: the white side starts at j = floor(u + 1.5) + 1
  // and the black side ends at j = -floor(1.5 - u) - 1. A pixel g is below the mid-level
  // (outside + inside) / 2 exactly when 4 g < mid4.
  const double u = (x0 - c) * in;
  const int whiteFrom = u < 0.5 ? 2 : 3, blackTo = u > -0.5 ? -2 : -3;
  const int mid4 = outside2 + inside2;
  int sum = 0;
  for (int j = -kHalfWindow; j <= kHalfWindow; ++j) {
    const int g = px(j);
    if ((j >= whiteFrom && 4 * g < mid4) || (j <= blackTo && 4 * g > mid4)) return false;
    sum += g;
  }
  const double white = (sum - (2 * kHalfWindow + 1) * outside) / contrast;
  const double edge = in > 0 ? c + (kHalfWindow + 0.5) - white : c - (kHalfWindow + 0.5) + white;
  if (!(std::abs(edge - x0) < 1.5)) return false;  // the window did not hold one clean edge
  x0 = edge;
  return true;
}

// The crossing nearest x0 of the grey level with the mean of the two plateaus sampled 2.5
// and 3.5 px either side of x0, the profile interpolated linearly between pixels.
bool linearCrossing(const PixelLine& line, int in, const EdgeLevels& levels, double& x0) {
  constexpr int kSearchPx = 3;
  double o1, o2, i1, i2;
  if (!line.interp(x0 - in * 2.5, o1) || !line.interp(x0 - in * 3.5, o2) ||
      !line.interp(x0 + in * 2.5, i1) || !line.interp(x0 + in * 3.5, i2))
    return false;
  const double outside = 0.5 * (o1 + o2), inside = 0.5 * (i1 + i2);
  if (!(inside - outside >= levels.minContrast())) return false;
  const double level = 0.5 * (inside + outside);
  const int k0 = floorToInt(x0);
  double best = 0.0;
  bool found = false;
  for (int k = std::max(k0 - kSearchPx, line.first); k <= std::min(k0 + kSearchPx, line.last - 1); ++k) {
    const double g0 = line.at(k), g1 = line.at(k + 1);
    // Only a rise towards white counts.
    if ((g1 - g0) * in <= 0.0 || (g0 - level) * (g1 - level) > 0.0) continue;
    const double x = k + (level - g0) / (g1 - g0);
    if (!found || std::abs(x - x0) < std::abs(best - x0)) best = x;
    found = true;
  }
  if (found) x0 = best;
  return found;
}

// A rim crossing near x0 on a grey line, `in` (+1 or -1) pointing towards white: the area
// estimate when its window holds one clean edge (once more if it moved the window's
// centre); otherwise the linear crossing, whose plateaus are re-centred on each new
// crossing until it settles (a start a pixel or two off the mid-level, as from a threshold
// near one class under blur), then the area estimate again if it now fits.
bool refineCrossing(const PixelLine& line, int in, const EdgeLevels& levels, double roomPx, double& x0) {
  constexpr int kMaxPasses = 4;
  // The area estimate alone when it settles: once more if it moved the window's centre.
  const double start = x0;
  if (areaCrossing(line, in, levels, roomPx, x0)) {
    if (roundToInt(x0) == roundToInt(start)) return true;
    const double first = x0;
    if (areaCrossing(line, in, levels, roomPx, x0) && std::abs(x0 - first) < 0.25) return true;
  }
  x0 = start;
  if (!linearCrossing(line, in, levels, x0)) return false;
  if (areaCrossing(line, in, levels, roomPx, x0)) return true;
  for (int pass = 1; pass < kMaxPasses; ++pass) {
    const double before = x0;
    if (!linearCrossing(line, in, levels, x0)) return false;
    if (std::abs(x0 - before) < 0.02) break;
  }
  return true;
}

// From `start` towards `end` (inwards) along a row or column: the first white pixel that
// follows a black one and is followed by another white one. Returns its coordinate or
// INT_MIN.
template <typename IsWhite>
int firstRimPixel(int start, int end, int in, IsWhite isWhite) {
  bool sawBlack = false;
  for (int k = start; k != end + in; k += in) {
    if (!isWhite(k)) {
      sawBlack = true;
    } else if (sawBlack && isWhite(k + in)) {
      return k;
    }
  }
  return INT32_MIN;
}

void fullPathOrg(const BinaryView& view, cv::Size imageSize, FeatureWorkspace& ws,
                 std::vector<Eigen::Vector2d>& out) {
  const cv::Rect& c = view.crop;
  reuseBuffer(ws.visited, c.size(), imageSize);  // an allocation the frame's size, kept
  ws.visited.setTo(0);
  auto take = [&](int x, int y) {
    std::uint8_t& seen = ws.visited.ptr<std::uint8_t>(y - c.y)[x - c.x];
    if (seen) return;
    seen = 1;
    out.emplace_back(x, y);
  };
  for (int y = c.y; y < c.y + c.height; ++y) {
    int first = -1, last = -1;
    for (int x = c.x; x < c.x + c.width; ++x)
      if (view.white(x, y)) {
        if (first < 0) first = x;
        last = x;
      }
    if (first >= 0) {
      take(first, y);
      take(last, y);
    }
  }
  for (int x = c.x; x < c.x + c.width; ++x) {
    int first = -1, last = -1;
    for (int y = c.y; y < c.y + c.height; ++y)
      if (view.white(x, y)) {
        if (first < 0) first = y;
        last = y;
      }
    if (first >= 0) {
      take(x, first);
      take(x, last);
    }
  }
}

void eightPointsOrg(const BinaryView& view, const Ellipse& detected,
                    std::vector<Eigen::Vector2d>& out) {
  static constexpr std::array<std::array<int, 2>, 8> kSteps{
      {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};
  const int x0 = roundToInt(detected.cx);
  const int y0 = roundToInt(detected.cy);
  const cv::Rect& c = view.crop;
  for (const auto& step : kSteps) {
    bool inWhite = false;
    int lx = 0, ly = 0;
    for (int x = x0, y = y0; c.contains(cv::Point(x, y)); x += step[0], y += step[1]) {
      if (view.white(x, y)) {
        inWhite = true;
        lx = x;
        ly = y;
      } else if (inWhite) {
        break;
      }
    }
    if (inWhite) out.emplace_back(lx, ly);
  }
}

void eightPointsMod(const BinaryView& view, const Ellipse& detected, double band,
                    std::vector<Eigen::Vector2d>& out) {
  const EllipseForm form(detected, 1.0);
  const double h = 1.0 / kRaySteps;
  for (int k = 0; k < 8; ++k) {
    const double ux = std::cos(k * M_PI / 4.0), uy = std::sin(k * M_PI / 4.0);
    const double te = form.rayLength(ux, uy);
    auto whiteAt = [&](double t) {
      return view.white(roundToInt(detected.cx + t * ux),
                        roundToInt(detected.cy + t * uy));
    };
    bool sawBlack = false;
    for (double t = te + band; t >= std::max(te - band, 0.0); t -= h) {
      if (!whiteAt(t)) {
        sawBlack = true;
      } else if (sawBlack && whiteAt(t - 1.0)) {
        const double tb = t + 0.5 * h;  // between the last black and the first white sample
        out.emplace_back(detected.cx + tb * ux, detected.cy + tb * uy);
        break;
      }
    }
  }
}

void fullPathMod(const ThresholdLines& lines, const cv::Rect& crop, const cv::Mat& grey, const Ellipse& detected,
                 double band, bool subPixel, const EdgeLevels& levels,
                 std::vector<Eigen::Vector2d>& out) {
  const EllipseForm form(detected, 1.0);
  const cv::Rect& c = crop;
  // SubPixel spaces its rows and columns a fractional step apart on a large rim: about
  // kSubPixelPoints evenly spread points (a rim crosses about 2 sqrt(2) (a + b) rows and
  // columns) are as good as all of them to a few per cent of the error and cost a fraction
  // of the time. A whole-pixel step would keep up to 1.4x as many.
  const double lineStep =
      subPixel ? std::max(1.0, 2.0 * M_SQRT2 * (detected.a + detected.b) / kSubPixelPoints) : 1.0;
  // One crossing of a row or column with the rim, expected at `e`, the run inside the rim
  // along that line being `run` long; `in` points towards the inside.
  // The detected rim lies off the grey edge by about the same distance all round (the
  // detection's threshold, taken in another region, sits nearer one class under blur): the
  // mean inward offset of the crossings refined so far starts the next one, so its first
  // area estimate usually holds one clean edge and settles at once.
  double offsetSum = 0.0;
  int offsetCount = 0;
  // The room the area estimate has (see areaCrossing): the run inside the rim, and the rim's
  // radius of curvature where the ellipse is curved tightly enough to matter (its least
  // radius is b^2 / a).
  const double tightest = std::min(detected.a, detected.b) * std::min(detected.a, detected.b) /
                          std::max(detected.a, detected.b);
  const bool curvatureMatters = subPixel && tightest < kAreaRoomPx;
  auto room = [&](double run, double x, double y) {
    return curvatureMatters && run >= kAreaRoomPx ? std::min(run, form.curvatureRadius(x, y)) : run;
  };
  auto crossing = [&](const PixelLine& binary, const PixelLine& greyLine, double e, int in, double roomPx,
                      double& at) {
    // SubPixel starts from the detected rim itself; only where the grey levels there show no
    // clean edge does it start again from the binary crossing.
    auto refined = [&] {
      if (!refineCrossing(greyLine, in, levels, roomPx, at)) return false;
      offsetSum += (at - e) * in;
      ++offsetCount;
      return true;
    };
    if (subPixel) {
      at = offsetCount > 0 ? e + in * offsetSum / offsetCount : e;
      if (refined()) return true;
    }
    const int start = roundToInt(e - in * band), end = roundToInt(e + in * band);
    const int k = firstRimPixel(start, end, in, [&](int j) { return binary.above(j, lines.level); });
    if (k == INT32_MIN) return false;
    at = k - in * 0.5;
    return !subPixel || refined();
  };
  // Rows cross the parts of the rim whose normal is closer to horizontal.
  for (double row = c.y; row < c.y + c.height; row += lineStep) {
    const int y = static_cast<int>(row);
    double xs[2];
    if (!form.rowCrossings(y, xs[0], xs[1])) continue;
    const PixelLine binary = lines.row(y), greyLine = PixelLine::row(grey, y);
    for (int side = 0; side < 2; ++side) {
      if (!form.normalMostlyHorizontal(xs[side], y)) continue;
      double x;
      if (crossing(binary, greyLine, xs[side], side == 0 ? 1 : -1, room(xs[1] - xs[0], xs[side], y), x))
        out.emplace_back(x, y);
    }
  }
  // Columns cross the rest.
  for (double column = c.x; column < c.x + c.width; column += lineStep) {
    const int x = static_cast<int>(column);
    double ys[2];
    if (!form.columnCrossings(x, ys[0], ys[1])) continue;
    const PixelLine binary = lines.column(x), greyLine = PixelLine::column(grey, x);
    for (int side = 0; side < 2; ++side) {
      if (form.normalMostlyHorizontal(x, ys[side])) continue;
      double y;
      if (crossing(binary, greyLine, ys[side], side == 0 ? 1 : -1, room(ys[1] - ys[0], x, ys[side]), y))
        out.emplace_back(x, y);
    }
  }
}

// Mean grey level of the classes [0, t] and [t+1, 255] of a histogram.
void classMeans(const Histogram& h, int t, double& dark, double& bright) {
  // Integer sums (exact, as the double sums of integers below 2^53 were), then one division.
  std::uint64_t n0 = 0, s0 = 0, n1 = 0, s1 = 0;
  const int split = std::clamp(t + 1, 0, 256);
  for (int g = 0; g < split; ++g) {
    n0 += h[g];
    s0 += static_cast<std::uint64_t>(g) * h[g];
  }
  for (int g = split; g < 256; ++g) {
    n1 += h[g];
    s1 += static_cast<std::uint64_t>(g) * h[g];
  }
  dark = n0 > 0 ? static_cast<double>(s0) / static_cast<double>(n0) : 0.0;
  bright = n1 > 0 ? static_cast<double>(s1) / static_cast<double>(n1) : 255.0;
}

int findRoot(std::vector<SpotRun>& runs, int i) {
  while (runs[i].parent != i) {
    runs[i].parent = runs[runs[i].parent].parent;
    i = runs[i].parent;
  }
  return i;
}

}  // namespace

double contourBandPx(const Ellipse& detected) { return 2.5 + 0.04 * detected.a; }

Status targetCrop(const Ellipse& e, int marginPx, cv::Size imageSize, cv::Rect& crop) {
  if (!(e.a > 0.0) || !(e.b > 0.0) || !std::isfinite(e.cx) || !std::isfinite(e.cy) ||
      !std::isfinite(e.a) || !std::isfinite(e.b) || !std::isfinite(e.angle_deg))
    return Status::OutOfImage;
  const double t = e.angle_deg * M_PI / 180.0;
  const double c = std::cos(t), s = std::sin(t);
  const double hx = std::sqrt(e.a * e.a * c * c + e.b * e.b * s * s);
  const double hy = std::sqrt(e.a * e.a * s * s + e.b * e.b * c * c);
  const double m = std::max(marginPx, 0);
  const double x0 = std::floor(e.cx - hx - m), x1 = std::ceil(e.cx + hx + m);
  const double y0 = std::floor(e.cy - hy - m), y1 = std::ceil(e.cy + hy + m);
  const double W = imageSize.width, H = imageSize.height;
  if (x1 < 0 || y1 < 0 || x0 >= W || y0 >= H) return Status::OutOfImage;
  const int ix0 = static_cast<int>(std::max(x0, 0.0)), iy0 = static_cast<int>(std::max(y0, 0.0));
  const int ix1 = static_cast<int>(std::min(x1, W - 1)), iy1 = static_cast<int>(std::min(y1, H - 1));
  crop = cv::Rect(ix0, iy0, ix1 - ix0 + 1, iy1 - iy0 + 1);
  return crop.area() > 0 ? Status::Ok : Status::OutOfImage;
}

Status rethresholdCrop(const cv::Mat& grey, const cv::Rect& crop, const ThresholdOptions& rethreshold,
                       int frameThreshold, FeatureWorkspace& ws, int& threshold, bool sampleRows) {
  if (grey.empty() || grey.type() != CV_8UC1) return Status::EmptyFrame;
  if ((crop & cv::Rect(0, 0, grey.cols, grey.rows)) != crop || crop.area() == 0)
    return Status::OutOfImage;
  // A near target's crop is large; its grey-level distribution, all the threshold and the
  // class means depend on, is the same on a regular subset of its rows: every k-th row,
  // at least kCropHistogramPixels pixels in all. (A view with a k times larger row step.)
  const int rowStep = sampleRows ? std::max(1, crop.area() / kCropHistogramPixels) : 1;
  const cv::Mat region = grey(crop);
  const cv::Mat sampled((crop.height + rowStep - 1) / rowStep, crop.width, CV_8UC1, region.data,
                        region.step[0] * static_cast<std::size_t>(rowStep));
  computeHistogram(sampled, ws.histogram);
  if (rethreshold.method == ThresholdMethod::None) {
    if (frameThreshold < 0 || frameThreshold > 255) return Status::InvalidSettings;
    threshold = frameThreshold;
  } else if (const Status s = computeThreshold(rethreshold, ws.histogram, threshold); !ok(s)) {
    return s;
  }
  ws.crop = crop;
  ws.threshold = threshold;
  classMeans(ws.histogram, threshold, ws.dark_mean, ws.bright_mean);
  return Status::Ok;
}

Status extractContour(ContourMode mode, const cv::Mat& grey, const cv::Rect& crop,
                      const Ellipse& detected, FeatureWorkspace& ws,
                      std::vector<Eigen::Vector2d>& points) {
  points.clear();
  if (grey.empty() || grey.type() != CV_8UC1 || ws.threshold < 0 || ws.crop != crop) return Status::EmptyFrame;
  const double band = contourBandPx(detected);
  if (mode == ContourMode::SubPixel) {
    // The grey frame itself, its binary crossing taken at the threshold on the fly.
    const EdgeLevels levels{ws.dark_mean, ws.bright_mean};
    fullPathMod(ThresholdLines{grey, {0, 0, grey.cols, grey.rows}, ws.threshold}, crop, grey, detected, band, true,
                levels, points);
    return points.size() >= 6 ? Status::Ok : Status::TooFewPoints;
  }
  binarizeCrop(grey, crop, ws.threshold, ws.binary);
  const BinaryView view{ws.binary, crop};
  switch (mode) {
    case ContourMode::EightPointsOrg: eightPointsOrg(view, detected, points); break;
    case ContourMode::EightPointsMod: eightPointsMod(view, detected, band, points); break;
    case ContourMode::FullPathOrg: fullPathOrg(view, grey.size(), ws, points); break;
    case ContourMode::FullPathMod:
      fullPathMod(ThresholdLines{ws.binary, crop, 0}, crop, grey, detected, band, false, EdgeLevels{}, points);
      break;
    case ContourMode::SubPixel: break;
  }
  return points.size() >= 6 ? Status::Ok : Status::TooFewPoints;
}

Status extractSpots(const cv::Mat& grey, const cv::Rect& crop, const Ellipse& detected,
                    const TargetGeometry& target, FeatureWorkspace& ws, SpotFeatures& spots) {
  spots.candidates = 0;
  if (grey.empty() || grey.type() != CV_8UC1 || ws.threshold < 0 || ws.crop != crop) return Status::EmptyFrame;
  const EllipseForm inner(detected, kSpotSearchScale);
  // Spots are cut at the middle of the crop's two class means rather than at the threshold
  // itself: a minimum-error threshold near one class's level (as under blur) would swell
  // or shrink them, and merge two spots seen close together.
  const double bright = ws.bright_mean;
  const auto spotLevel = static_cast<std::uint8_t>(std::clamp(floorToInt(0.5 * (ws.dark_mean + ws.bright_mean)), 0, 255));
  std::vector<SpotRun>& runs = ws.runs;
  runs.clear();
  std::vector<int>& bounds = ws.runBounds;
  bounds.resize(static_cast<std::size_t>(crop.width) + 2);  // a row's runs at most
  const DarkRowScan scan = darkRowScanForThisProcessor();
  // Black runs inside the search ellipse, row by row; each run is joined to the
  // 8-connected runs of the row above. Rows are first tested kGroup at a time for any dark
  // pixel over the union of their spans (their minimum, one comparison per block for all of
  // them): most rows of the disk have none, and a group without one has no runs.
  constexpr int kGroup = 4;
  // The group's span: the search ellipse's left crossing is convex and its right one concave
  // in y, so over a group they reach beyond their values at its end rows only about the
  // ellipse's leftmost or rightmost point, where its full width is taken; a pixel more either
  // side covers rounding. A wider span only sends more groups to the row-by-row search.
  const double halfWidth = std::sqrt(inner.R / (inner.P * inner.R - inner.Q * inner.Q));
  const double yLeftmost = inner.cy + inner.Q * halfWidth / inner.R;
  const double yRightmost = inner.cy - inner.Q * halfWidth / inner.R;
  std::array<const std::uint8_t*, kGroup> groupRows{};
  std::size_t prevBegin = 0, prevEnd = 0;
  for (int r0 = 0; r0 < crop.height; r0 += kGroup) {
    const int n = std::min(kGroup, crop.height - r0);
    const int yA = crop.y + r0, yB = yA + n - 1;
    double leftA, rightA, leftB, rightB;
    if (n == kGroup && inner.rowCrossings(yA, leftA, rightA) && inner.rowCrossings(yB, leftB, rightB)) {
      double left = std::min(leftA, leftB), right = std::max(rightA, rightB);
      if (yLeftmost > yA - 1 && yLeftmost < yB + 1) left = inner.cx - halfWidth;
      if (yRightmost > yA - 1 && yRightmost < yB + 1) right = inner.cx + halfWidth;
      const int x0 = std::max(floorToInt(left) - 1, crop.x) - crop.x;
      const int x1 = std::min(ceilToInt(right) + 1, crop.x + crop.width - 1) - crop.x;
      for (int k = 0; k < n; ++k) groupRows[k] = grey.ptr<std::uint8_t>(yA + k) + crop.x;
      if (x0 > x1 || !scan.any(groupRows.data(), n, x0, x1, spotLevel, -crop.x)) {
        prevBegin = prevEnd = runs.size();  // rows without runs
        continue;
      }
    }
    for (int k = 0; k < n; ++k) {
      const int r = r0 + k, y = crop.y + r;
      const std::size_t rowBegin = runs.size();
      double xl, xr;
      int count = 0;
      if (inner.rowCrossings(y, xl, xr)) {
        const int x0 = std::max(ceilToInt(xl), crop.x) - crop.x;
        const int x1 = std::min(floorToInt(xr), crop.x + crop.width - 1) - crop.x;
        const std::uint8_t* row = grey.ptr<std::uint8_t>(y) + crop.x;
        count = x0 <= x1 ? scan.runs(row, x0, x1, spotLevel, -crop.x, bounds.data()) : 0;
      }
      for (int i = 0; i < count; ++i) {
        const int start = bounds[2 * i], x = bounds[2 * i + 1] + 1;
        const int id = static_cast<int>(runs.size());
        runs.push_back({r, start, x - 1, id});
        for (std::size_t p = prevBegin; p < prevEnd; ++p) {
          if (runs[p].x0 <= x && runs[p].x1 >= start - 1) {
            const int a = findRoot(runs, static_cast<int>(p)), b = findRoot(runs, id);
            if (a != b) runs[std::max(a, b)].parent = std::min(a, b);
          }
        }
      }
      prevBegin = rowBegin;
      prevEnd = runs.size();
    }
  }

  // Components: area and box of every set of joined runs.
  std::vector<int>& componentOf = ws.componentOf;
  std::vector<SpotComponent>& components = ws.components;
  componentOf.assign(runs.size(), -1);
  components.clear();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const int root = findRoot(runs, static_cast<int>(i));
    const SpotRun& run = runs[i];
    if (componentOf[root] < 0) {
      componentOf[root] = static_cast<int>(components.size());
      components.push_back({0, run.x0, run.row, run.x1, run.row});
    }
    SpotComponent& c = components[componentOf[root]];
    c.area += run.x1 - run.x0 + 1;
    c.x0 = std::min(c.x0, run.x0);
    c.x1 = std::max(c.x1, run.x1);
    c.y0 = std::min(c.y0, run.row);
    c.y1 = std::max(c.y1, run.row);
  }
  // Of spot size: between 1/5 and 5 times the expected area.
  const double expected =
      M_PI * std::pow(target.spot_radius_mm / target.radius_mm, 2) * detected.a * detected.b;
  const double minArea = std::max(2.0, 0.2 * expected), maxArea = 5.0 * expected + 4.0;
  std::array<SpotComponent, 2> kept{};
  int accepted = 0;
  for (const SpotComponent& c : components) {
    if (c.area < minArea || c.area > maxArea) continue;
    if (accepted < 2) kept[accepted] = c;
    ++accepted;
  }
  spots.candidates = accepted;
  if (accepted < 2) {
    // Too small or faint to be cut at the mid level: where the geometry puts them.
    std::array<cv::Rect, 2> boxes;
    if (!spotBoxesByModel(grey, detected, target, bright, ws.dark_mean, boxes)) return Status::SpotsNotFound;
    for (int k = 0; k < 2; ++k)
      kept[k] = {boxes[k].area(), boxes[k].x - crop.x, boxes[k].y - crop.y, boxes[k].x + boxes[k].width - 1 - crop.x,
                 boxes[k].y + boxes[k].height - 1 - crop.y};
    accepted = 2;
  }
  if (accepted > 2) return Status::AmbiguousSpots;

  // Darkness-weighted centroids over each box grown by a few pixels, leaving out what lies
  // near or beyond the rim (the dark card would pull a spot seen close to it, as on a target
  // seen obliquely).
  const EllipseForm rim(detected, 1.0);
  const double rhoMax = std::max(0.5, 1.0 - kSpotRimClearancePx / detected.b);
  const double rho2Max = rhoMax * rhoMax;
  std::array<Eigen::Vector2d, 2> centroid;
  for (int k = 0; k < 2; ++k) {
    const SpotComponent& cmp = kept[k];
    const cv::Rect box = cv::Rect(crop.x + cmp.x0 - kSpotBoxGrowPx, crop.y + cmp.y0 - kSpotBoxGrowPx,
                                  cmp.x1 - cmp.x0 + 1 + 2 * kSpotBoxGrowPx,
                                  cmp.y1 - cmp.y0 + 1 + 2 * kSpotBoxGrowPx) &
                         cv::Rect(0, 0, grey.cols, grey.rows);
    // The ellipse is convex: with the box's corners inside, every pixel is.
    const int bx1 = box.x + box.width - 1, by1 = box.y + box.height - 1;
    const bool boxInside = rim.rho2(box.x, box.y) < rho2Max && rim.rho2(bx1, box.y) < rho2Max &&
                           rim.rho2(box.x, by1) < rho2Max && rim.rho2(bx1, by1) < rho2Max;
    // The local white level: the box's border pixels inside the rim.
    double borderSum = 0.0;
    int borderCount = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      const bool edgeRow = y == box.y || y == box.y + box.height - 1;
      for (int x = box.x; x < box.x + box.width; x += edgeRow ? 1 : std::max(box.width - 1, 1)) {
        if (!boxInside && rim.rho2(x, y) >= rho2Max) continue;
        borderSum += row[x];
        ++borderCount;
      }
    }
    const double white = borderCount > 0 ? borderSum / borderCount : bright;
    // Weights white - g: summed as integer moments of g (sum g, sum x g, sum y g over n
    // pixels), combined with the white level at the end.
    std::int64_t n = 0, sumX = 0, sumY = 0, sumG = 0, sumXG = 0, sumYG = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      std::int64_t rowN = 0, rowX = 0, rowG = 0, rowXG = 0;
      if (boxInside) {
        std::int64_t rowIG = 0;
        rowMoments(row + box.x, box.width, rowG, rowIG);
        rowN = box.width;
        const std::int64_t width = box.width;
        rowX = width * box.x + width * (width - 1) / 2;
        rowXG = box.x * rowG + rowIG;
      } else {
        for (int x = box.x; x < box.x + box.width; ++x) {
          if (rim.rho2(x, y) >= rho2Max) continue;
          ++rowN;
          rowX += x;
          rowG += row[x];
          rowXG += static_cast<std::int64_t>(x) * row[x];
        }
      }
      n += rowN;
      sumX += rowX;
      sumY += rowN * y;
      sumG += rowG;
      sumXG += rowXG;
      sumYG += static_cast<std::int64_t>(rowG) * y;
    }
    const double sw = white * static_cast<double>(n) - static_cast<double>(sumG);
    const double sx = white * static_cast<double>(sumX) - static_cast<double>(sumXG);
    const double sy = white * static_cast<double>(sumY) - static_cast<double>(sumYG);
    if (!(sw > 0.0)) return Status::SpotsNotFound;
    centroid[k] = Eigen::Vector2d(sx / sw, sy / sw);
  }
  const bool firstIsCentre =
      rim.rho2(centroid[0].x(), centroid[0].y()) <= rim.rho2(centroid[1].x(), centroid[1].y());
  spots.centre_spot = centroid[firstIsCentre ? 0 : 1];
  spots.offset_spot = centroid[firstIsCentre ? 1 : 0];
  return Status::Ok;
}

}  // namespace imagepro
