// Feature extraction: the search for the two spots and their centroids (features.h).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "core/common/contract.h"
#include "core/common/simd_level.h"
#include "core/reconstruction/feature_geometry.h"
#include "core/reconstruction/features.h"
#include "core/reconstruction/spot_model.h"

namespace imagepro {

using feature_detail::ceilToInt;
using feature_detail::EllipseForm;
using feature_detail::floorToInt;

namespace {

constexpr double kSpotSearchScale = 0.85;  // spots are searched inside 0.85 of the rim
constexpr int kSpotBoxGrowPx = 3;
constexpr int kDetectedSpotGrowPx = 1;
constexpr double kSpotRimClearancePx = 2.5;  // spot centroids ignore pixels this near the rim
// The weighted centre's window: a Gaussian of this fraction of the spot's expected radius
// (measured on real-scene frames: 0.5-0.85 do alike, 1.3 loses a third of the gain).
constexpr double kSpotWindowScale = 0.7;
constexpr int kSpotWindowMaxPx = 128;  // wider boxes (spots over ~50 px) keep the plain centroid
// A saturated pixel is glare; so is one brighter than the paper round the spot (its box's
// border) by this share of the paper-to-card contrast, and at least this many grey levels
// (over three times the noise of a webcam's frame). The crop's bright class mean is no
// measure of the paper: on a small target it takes in the blurred rim.
constexpr int kSaturatedGrey = 250;
constexpr double kGlareAboveLocal = 0.15;
constexpr double kGlareAboveLocalGrey = 20.0;
// More than two dark components on the disk (an occluder's end, a shadow's edge): the pair
// that sits where the target's spots sit is taken, within this share of the rim's radius
// (as the ellipse stage's default spot tolerance), of areas within kPairAreaRatio, when it
// sits better than any other pair by kClearlyBestPair (chooseSpots).
constexpr double kSpotPlaceTolerance = 0.2;
constexpr double kPairAreaRatio = 3.0;
constexpr double kClearlyBestPair = 1.0;
// The disk's own levels (diskLevels) need this many pixels, and this contrast between its
// paper and its darkest, to cut spots at their middle.
constexpr int kMinDiskPixels = 64;
constexpr double kMinDiskContrast = 24.0;

// The darkness-weighted centroid under a Gaussian window that follows it (a matched-filter
// centre): each pass weighs a pixel by (white - g) exp(-|p - u|^2 / 2 s^2) about the last
// centre u. The plain centroid weighs every pixel of the box alike, so the noise, JPEG
// blocks and light slope of the white pixels around a small spot move it; the window
// keeps the weight on the spot itself. Symmetric about the spot, the window adds no bias.
// Returns false (centre unchanged) when the weights vanish or the centre wanders off.
template <typename Counts>
bool weightedSpotCentre(const cv::Mat& grey, const cv::Rect& box, const Counts& counts, double white,
                        double windowPx, Eigen::Vector2d& centre) {
  if (box.width > kSpotWindowMaxPx || box.height > kSpotWindowMaxPx || !(windowPx > 0.0)) return false;
  std::array<double, kSpotWindowMaxPx> wx{}, wy{};
  const double inv2s2 = 0.5 / (windowPx * windowPx);
  Eigen::Vector2d u = centre;
  constexpr int kPasses = 8;
  for (int pass = 0; pass < kPasses; ++pass) {
    // The window is separable: one exponential per column and per row.
    for (int i = 0; i < box.width; ++i) wx[i] = std::exp(-(box.x + i - u.x()) * (box.x + i - u.x()) * inv2s2);
    for (int j = 0; j < box.height; ++j) wy[j] = std::exp(-(box.y + j - u.y()) * (box.y + j - u.y()) * inv2s2);
    double w0 = 0.0, w1x = 0.0, w1y = 0.0;
    for (int j = 0; j < box.height; ++j) {
      const int y = box.y + j;
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      double r0 = 0.0, r1x = 0.0;
      for (int i = 0; i < box.width; ++i) {
        const int x = box.x + i;
        if (!counts(x, y)) continue;
        const double w = (white - row[x]) * wx[i];
        r0 += w;
        r1x += w * x;
      }
      w0 += r0 * wy[j];
      w1x += r1x * wy[j];
      w1y += r0 * wy[j] * y;
    }
    if (!(w0 > 0.0)) return false;
    const Eigen::Vector2d next(w1x / w0, w1y / w0);
    if ((next - centre).norm() > 2.0) return false;
    const bool settled = (next - u).norm() < 1e-3;
    u = next;
    if (settled) break;
  }
  centre = u;
  return true;
}

// The spot search's row scan (dark_runs_pass.inc), once per vector width: the widest the
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
#include "core/reconstruction/dark_runs_pass.inc"
}  // namespace sse2

IMAGEPRO_AVX2_BEGIN
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
#include "core/reconstruction/dark_runs_pass.inc"
}  // namespace avx2
IMAGEPRO_AVX2_END
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
#include "core/reconstruction/dark_runs_pass.inc"
}  // namespace scalar
#endif

struct DarkRowScan {
  int (*runs)(const std::uint8_t*, int, int, std::uint8_t, int, int*);
  bool (*any)(const std::uint8_t* const*, int, int, int, std::uint8_t, int);
};

DarkRowScan darkRowScanForThisProcessor() {
#if defined(__SSE2__)
  if (simdAllows(SimdLevel::Avx2)) return {&avx2::darkRuns, &avx2::anyDark};
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

int findRoot(std::vector<SpotRun>& runs, int i) {
  while (runs[i].parent != i) {
    runs[i].parent = runs[runs[i].parent].parent;
    i = runs[i].parent;
  }
  return i;
}

// The dark components inside the search ellipse `inner` of the crop, cut at `level`, into
// ws.components (ws.runs and ws.componentOf are its scratch).
void darkComponents(const cv::Mat& grey, const cv::Rect& crop, const EllipseForm& inner, std::uint8_t spotLevel,
                    FeatureWorkspace& ws) {
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
      const int first = count > 0 ? std::max(ceilToInt(xl), crop.x) - crop.x : 0;
      const int last = count > 0 ? std::min(floorToInt(xr), crop.x + crop.width - 1) - crop.x : 0;
      for (int i = 0; i < count; ++i) {
        const int start = bounds[2 * i], x = bounds[2 * i + 1] + 1;
        const int id = static_cast<int>(runs.size());
        runs.push_back({r, start, x - 1, id, start <= first || x - 1 >= last});
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
      components.push_back({0, run.x0, run.row, run.x1, run.row, false});
    }
    SpotComponent& c = components[componentOf[root]];
    c.at_limit = c.at_limit || run.at_limit;
    c.area += run.x1 - run.x0 + 1;
    c.x0 = std::min(c.x0, run.x0);
    c.x1 = std::max(c.x1, run.x1);
    c.y0 = std::min(c.y0, run.row);
    c.y1 = std::max(c.y1, run.row);
  }
}

// How far dark components c (the centre spot) and f (the offset spot), crop coordinates
// from `origin`, sit from where the target's spots sit on `rim`: the centre spot's distance
// from the centre and the error of their distance, in units of kSpotPlaceTolerance of the
// rim's radius, plus their areas' ratio on the log scale of kPairAreaRatio. Infinite when a
// measure is beyond its tolerance.
double spotsMisfit(const SpotComponent& c, const SpotComponent& f, cv::Point origin, const EllipseForm& rim,
                   const TargetGeometry& target) {
  constexpr double kOut = std::numeric_limits<double>::infinity();
  const double areas = std::abs(std::log(static_cast<double>(c.area) / f.area)) / std::log(kPairAreaRatio);
  if (areas > 1.0) return kOut;
  auto centre = [&](const SpotComponent& k) {
    return Eigen::Vector2d(origin.x + 0.5 * (k.x0 + k.x1), origin.y + 0.5 * (k.y0 + k.y1));
  };
  const Eigen::Vector2d pc = centre(c), pf = centre(f), d = pf - pc;
  const double rc = std::sqrt(rim.rho2(pc.x(), pc.y()));
  const double apartError = std::abs(std::sqrt(rim.norm2(d.x(), d.y())) - target.spot_offset_mm / target.radius_mm);
  if (rc > kSpotPlaceTolerance || std::sqrt(rim.rho2(pf.x(), pf.y())) < rc || apartError > kSpotPlaceTolerance)
    return kOut;
  return (rc + apartError) / kSpotPlaceTolerance + areas;
}

std::uint8_t levelAt(double grey) { return static_cast<std::uint8_t>(std::clamp(floorToInt(grey), 0, 255)); }

// The two spots among the dark components (crop coordinates from `origin`): of spot size,
// between 1/5 and 5 times the expected area. Those reaching the search's edge are taken only
// when, with them, there are exactly two: a spot of a small, steeply seen target can reach
// it too. Of more than two inside the search, the pair in place (spotsMisfit) is taken when
// no other is nearly as well in place.
// True with the pair in `kept`; `candidates` counts the components of spot size.
bool chooseSpots(const std::vector<SpotComponent>& components, cv::Point origin, const Ellipse& detected,
                 const TargetGeometry& target, double expected, std::array<SpotComponent, 2>& kept, int& candidates) {
  const double minArea = std::max(2.0, 0.2 * expected), maxArea = 5.0 * expected + 4.0;
  auto ofSpotSize = [&](const SpotComponent& c) { return c.area >= minArea && c.area <= maxArea; };
  std::array<SpotComponent, 2> withEdge{};
  int accepted = 0, touching = 0;
  for (const SpotComponent& c : components) {
    if (!ofSpotSize(c)) continue;
    if (accepted + touching < 2) withEdge[accepted + touching] = c;
    if (c.at_limit) {
      ++touching;
      continue;
    }
    if (accepted < 2) kept[accepted] = c;
    ++accepted;
  }
  candidates = accepted;
  if (accepted < 2 && accepted + touching == 2) {
    kept = withEdge;
    candidates = 2;
    return true;
  }
  if (accepted <= 2) return accepted == 2;
  // Of several pairs in place, the best, when clearly so.
  const EllipseForm rim(detected, 1.0);
  double best = std::numeric_limits<double>::infinity(), second = best;
  for (const SpotComponent& c : components) {
    if (!ofSpotSize(c) || c.at_limit) continue;
    for (const SpotComponent& f : components) {
      if (&f == &c || !ofSpotSize(f) || f.at_limit) continue;
      const double misfit = spotsMisfit(c, f, origin, rim, target);
      if (misfit < best) {
        second = best;
        best = misfit;
        kept = {c, f};
      } else {
        second = std::min(second, misfit);
      }
    }
  }
  return std::isfinite(best) && second > best + kClearlyBestPair;
}

// The paper's level on the disk (the upper quartile of the grey levels inside the search
// ellipse `inner`: spots and an occluder's part take less than that) and its darkest (the
// 2nd percentile: the spots' cores). False with too few pixels to tell.
bool diskLevels(const cv::Mat& grey, const cv::Rect& crop, const EllipseForm& inner, double& paper, double& darkest) {
  std::array<int, 256> counts{};
  int n = 0;
  for (int y = crop.y; y < crop.y + crop.height; ++y) {
    double xl, xr;
    if (!inner.rowCrossings(y, xl, xr)) continue;
    const int x0 = std::max(ceilToInt(xl), crop.x), x1 = std::min(floorToInt(xr), crop.x + crop.width - 1);
    const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
    for (int x = x0; x <= x1; ++x) ++counts[row[x]];
    n += std::max(0, x1 - x0 + 1);
  }
  if (n < kMinDiskPixels) return false;
  auto percentile = [&](double share) {
    const int want = static_cast<int>(share * n);
    int seen = 0;
    for (int g = 0; g < 256; ++g)
      if ((seen += counts[static_cast<std::size_t>(g)]) > want) return static_cast<double>(g);
    return 255.0;
  };
  paper = percentile(0.75);
  darkest = percentile(0.02);
  return true;
}

}  // namespace

Status extractSpots(const cv::Mat& grey, const cv::Rect& crop, const Ellipse& detected,
                    const TargetGeometry& target, bool weightedCentres, FeatureWorkspace& ws,
                    SpotFeatures& spots, const std::array<cv::Rect, 2>* detectedSpots) {
  spots.candidates = 0;
  // The crop was checked against the frame rethresholdCrop saw; reading another, smaller
  // frame through it would run past its rows.
  IMAGEPRO_EXPECTS(grey.empty() || (crop & cv::Rect(0, 0, grey.cols, grey.rows)) == crop,
                   "the crop lies inside the frame rethresholdCrop was given");
  if (grey.empty() || grey.type() != CV_8UC1 || ws.threshold < 0 || ws.crop != crop) return Status::EmptyFrame;
  const EllipseForm inner(detected, kSpotSearchScale);
  // Spots are cut at the middle of the crop's two class means rather than at the threshold
  // itself: a minimum-error threshold near one class's level (as under blur) would swell
  // or shrink them, and merge two spots seen close together.
  double dark = ws.dark_mean, bright = ws.bright_mean;
  const double expected =
      M_PI * std::pow(target.spot_radius_mm / target.radius_mm, 2) * detected.a * detected.b;
  std::array<SpotComponent, 2> kept{};
  darkComponents(grey, crop, inner, levelAt(0.5 * (dark + bright)), ws);
  bool chosen = chooseSpots(ws.components, crop.tl(), detected, target, expected, kept, spots.candidates);
  // A dim target before a bright scene: the crop's bright class is the scene's, and the
  // paper falls below the mid level with the spots. The disk's own levels then decide:
  // its paper and its darkest (the spots, as dark as the card).
  double paper = 0.0, darkest = 0.0;
  if (!chosen && diskLevels(grey, crop, inner, paper, darkest) && paper <= 0.5 * (dark + bright) &&
      paper - darkest >= kMinDiskContrast) {
    dark = darkest;
    bright = paper;
    darkComponents(grey, crop, inner, levelAt(0.5 * (dark + bright)), ws);
    chosen = chooseSpots(ws.components, crop.tl(), detected, target, expected, kept, spots.candidates);
  }
  // A component that reaches the search's edge is a spot only for want of another: the
  // detection's pair, found with the rim, is the better word then.
  const bool byEdge = chosen && (kept[0].at_limit || kept[1].at_limit);
  bool fromDetection = false;
  if ((!chosen || byEdge) && detectedSpots && ((*detectedSpots)[0] & crop) == (*detectedSpots)[0] &&
      ((*detectedSpots)[1] & crop) == (*detectedSpots)[1] && !(*detectedSpots)[0].empty() &&
      !(*detectedSpots)[1].empty()) {
    for (int k = 0; k < 2; ++k) {
      const cv::Rect& box = (*detectedSpots)[static_cast<std::size_t>(k)];
      kept[static_cast<std::size_t>(k)] = {box.area(), box.x - crop.x, box.y - crop.y, box.x + box.width - 1 - crop.x,
                                           box.y + box.height - 1 - crop.y, false};
    }
    chosen = fromDetection = true;
  }
  if (!chosen && spots.candidates > 2) return Status::AmbiguousSpots;
  if (!chosen) {
    // Too small or faint to be cut at the mid level: where the geometry puts them.
    std::array<cv::Rect, 2> boxes;
    if (!spotBoxesByModel(grey, detected, target, bright, dark, boxes)) return Status::SpotsNotFound;
    for (int k = 0; k < 2; ++k)
      kept[k] = {boxes[k].area(), boxes[k].x - crop.x, boxes[k].y - crop.y, boxes[k].x + boxes[k].width - 1 - crop.x,
                 boxes[k].y + boxes[k].height - 1 - crop.y, false};
  }

  // Darkness-weighted centroids over each box grown by a few pixels, leaving out what lies
  // near or beyond the rim (the dark card would pull a spot seen close to it, as on a target
  // seen obliquely).
  const EllipseForm rim(detected, 1.0);
  const double rhoMax = std::max(0.5, 1.0 - kSpotRimClearancePx / detected.b);
  const double rho2Max = rhoMax * rhoMax;
  // A detection's spot box holds a ring of paper already, and what lies beyond it may be
  // the occluder the crop's cut joined to the spot.
  const int grow = fromDetection ? kDetectedSpotGrowPx : kSpotBoxGrowPx;
  auto grownBox = [&](const SpotComponent& cmp) {
    return cv::Rect(crop.x + cmp.x0 - grow, crop.y + cmp.y0 - grow, cmp.x1 - cmp.x0 + 1 + 2 * grow,
                    cmp.y1 - cmp.y0 + 1 + 2 * grow) &
           cv::Rect(0, 0, grey.cols, grey.rows);
  };
  // On a small, far target the two spots lie a few pixels apart and each grown box holds
  // part of the other spot, which would pull both centroids towards each other. Each box
  // then keeps only the pixels on its own side of the line halfway between the two spots:
  // what that cuts off of a spot's own blur lies beyond half their distance and weighs
  // little.
  const bool boxesOverlap = (grownBox(kept[0]) & grownBox(kept[1])).area() > 0;
  auto boxCentre = [&](const SpotComponent& cmp) {
    return Eigen::Vector2d(crop.x + 0.5 * (cmp.x0 + cmp.x1), crop.y + 0.5 * (cmp.y0 + cmp.y1));
  };
  const Eigen::Vector2d midway = 0.5 * (boxCentre(kept[0]) + boxCentre(kept[1]));
  // A glare (saturated, or far above the paper) is neither paper nor spot: it is left out of
  // the white level and of the centroid, whose weights white - g it would turn negative,
  // pushing the spot away from it.
  std::array<Eigen::Vector2d, 2> centroid;
  for (int k = 0; k < 2; ++k) {
    const cv::Rect box = grownBox(kept[k]);
    const Eigen::Vector2d towardsOther = boxCentre(kept[1 - k]) - boxCentre(kept[k]);
    // Whether a pixel counts: inside the rim's clearance, on this spot's side, and (once the
    // paper's level is known) no glare.
    auto within = [&](int x, int y) {
      return rim.rho2(x, y) < rho2Max &&
             (!boxesOverlap || (Eigen::Vector2d(x, y) - midway).dot(towardsOther) < 0.0);
    };
    int brightest = 0;  // the box's brightest pixel
    for (int y = box.y; y < box.y + box.height; ++y) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      brightest = std::max<int>(brightest, *std::max_element(row + box.x, row + box.x + box.width));
    }
    int glareCut = kSaturatedGrey;
    bool glare = brightest > glareCut;
    auto counts = [&](int x, int y) { return within(x, y) && (!glare || grey.at<std::uint8_t>(y, x) <= glareCut); };
    // The ellipse is convex: with the box's corners inside, every pixel is.
    const int bx1 = box.x + box.width - 1, by1 = box.y + box.height - 1;
    const bool cornersInside = !boxesOverlap && rim.rho2(box.x, box.y) < rho2Max && rim.rho2(bx1, box.y) < rho2Max &&
                               rim.rho2(box.x, by1) < rho2Max && rim.rho2(bx1, by1) < rho2Max;
    bool boxInside = cornersInside && !glare;
    // The local white level: the box's border pixels inside the rim.
    double borderSum = 0.0;
    int borderCount = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      const bool edgeRow = y == box.y || y == box.y + box.height - 1;
      for (int x = box.x; x < box.x + box.width; x += edgeRow ? 1 : std::max(box.width - 1, 1)) {
        if (!boxInside && !counts(x, y)) continue;
        borderSum += row[x];
        ++borderCount;
      }
    }
    if (borderCount < 4) {
      // The box's border lies beyond the rim's clearance or the other spot's half (a small,
      // tilted target): the paper is read instead on the box's pixels that count and lie
      // clear of the spot (the crop's bright class mean takes in the blurred rim and lies
      // below the paper, which would leave the spot without weight).
      const Eigen::Vector2d spotCentre = boxCentre(kept[k]);
      const double clear = target.spot_radius_mm / target.radius_mm * detected.a + 1.5;
      borderSum = 0.0;
      borderCount = 0;
      for (int y = box.y; y < box.y + box.height; ++y) {
        const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
        for (int x = box.x; x < box.x + box.width; ++x) {
          if (!counts(x, y) || (Eigen::Vector2d(x, y) - spotCentre).norm() < clear) continue;
          borderSum += row[x];
          ++borderCount;
        }
      }
    }
    const double white = borderCount > 0 ? borderSum / borderCount : bright;
    // Glare's halo, short of saturation, also lies above the paper round the spot: left out
    // from a fraction of the paper-to-card contrast above it (noise seldom reaches that far).
    glareCut = std::min(kSaturatedGrey,
                        floorToInt(white + std::max(kGlareAboveLocalGrey, kGlareAboveLocal * (white - dark))));
    glare = brightest > glareCut;
    boxInside = cornersInside && !glare;
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
          if (!counts(x, y)) continue;
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
    if (weightedCentres) {
      const double windowPx = kSpotWindowScale * std::max(1.0, target.spot_radius_mm / target.radius_mm * detected.a);
      if (boxInside)
        weightedSpotCentre(grey, box, [](int, int) { return true; }, white, windowPx, centroid[k]);
      else
        weightedSpotCentre(grey, box, counts, white, windowPx, centroid[k]);
    }
  }
  const bool firstIsCentre =
      rim.rho2(centroid[0].x(), centroid[0].y()) <= rim.rho2(centroid[1].x(), centroid[1].y());
  spots.centre_spot = centroid[firstIsCentre ? 0 : 1];
  spots.offset_spot = centroid[firstIsCentre ? 1 : 0];
  return Status::Ok;
}

}  // namespace imagepro
