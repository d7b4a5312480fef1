// Feature extraction: the rim's contour points in each contour mode (features.h).
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/common/contract.h"
#include "core/reconstruction/feature_geometry.h"
#include "core/reconstruction/features.h"
#include "core/reconstruction/rim_edge.h"
#include "core/segmentation/image_buffer.h"

namespace imagepro {

using feature_detail::ceilToInt;
using feature_detail::EllipseForm;
using feature_detail::floorToInt;
using feature_detail::levelCrossing;
using feature_detail::PixelLine;
using feature_detail::roundToInt;

namespace {

constexpr double kRaySteps = 16.0;  // 8 points MOD: samples per pixel along a ray
constexpr double kMinSubPixelContrastFraction = 0.3;
constexpr double kSubPixelPoints = 160.0;
// Near head-on the plane's normal hangs on the rim's slight ellipticity (its error grows as
// the square root of the fitted axes' error), so without the rim edge model a rim within
// about 20 deg of round (b >= 0.94 a) takes up to twice the points. The model's points are
// about twice as precise, and 160 of them meet the head-on goals at less cost:
// docs/reconstruction.md, Accuracy study and Rim edge model.
constexpr double kHeadOnSubPixelPoints = 320.0;
constexpr double kHeadOnAxisRatio = 0.94;

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
  double o1, o2, i1, i2;
  if (!line.interp(x0 - in * 2.5, o1) || !line.interp(x0 - in * 3.5, o2) ||
      !line.interp(x0 + in * 2.5, i1) || !line.interp(x0 + in * 3.5, i2))
    return false;
  const double outside = 0.5 * (o1 + o2), inside = 0.5 * (i1 + i2);
  if (!(inside - outside >= levels.minContrast())) return false;
  return levelCrossing(line, in, 0.5 * (inside + outside), x0);
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

// A crossing's start for the rim edge model, which places it again: the area estimate
// once, else the linear crossing until it settles (a far rim's start may lie a pixel off),
// without refineCrossing's second looks at the area estimate.
bool startCrossing(const PixelLine& line, int in, const EdgeLevels& levels, double roomPx, double& x0) {
  constexpr int kMaxPasses = 4;
  const double start = x0;
  if (areaCrossing(line, in, levels, roomPx, x0)) return true;
  x0 = start;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
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

// `crossings` (SubPixel) receives each point's line, in the points' order. With
// `modelFollows` the rim edge model places the points again: each crossing needs only a
// start (startCrossing), and a near-round rim keeps kSubPixelPoints.
void fullPathMod(const ThresholdLines& lines, const cv::Rect& crop, const cv::Mat& grey, const Ellipse& detected,
                 double band, bool subPixel, const EdgeLevels& levels, std::vector<Eigen::Vector2d>& out,
                 std::vector<RimCrossing>* crossings = nullptr, bool modelFollows = false) {
  const EllipseForm form(detected, 1.0);
  const cv::Rect& c = crop;
  // SubPixel spaces its rows and columns a fractional step apart on a large rim: about
  // kSubPixelPoints evenly spread points (a rim crosses about 2 sqrt(2) (a + b) rows and
  // columns) are as good as all of them to a few per cent of the error on a tilted target
  // and cost a fraction of the time. A whole-pixel step would keep up to 1.4x as many.
  const double points =
      !modelFollows && detected.b >= kHeadOnAxisRatio * detected.a ? kHeadOnSubPixelPoints : kSubPixelPoints;
  const double lineStep = subPixel ? std::max(1.0, 2.0 * M_SQRT2 * (detected.a + detected.b) / points) : 1.0;
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
      if (!(modelFollows ? startCrossing(greyLine, in, levels, roomPx, at)
                         : refineCrossing(greyLine, in, levels, roomPx, at)))
        return false;
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
      const int in = side == 0 ? 1 : -1;
      if (crossing(binary, greyLine, xs[side], in, room(xs[1] - xs[0], xs[side], y), x)) {
        out.emplace_back(x, y);
        if (crossings) crossings->push_back({y, in, true});
      }
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
      const int in = side == 0 ? 1 : -1;
      if (crossing(binary, greyLine, ys[side], in, room(ys[1] - ys[0], x, ys[side]), y)) {
        out.emplace_back(x, y);
        if (crossings) crossings->push_back({x, in, false});
      }
    }
  }
}

}  // namespace

double contourBandPx(const Ellipse& detected) { return 2.5 + 0.04 * detected.a; }

Status extractContour(ContourMode mode, const cv::Mat& grey, const cv::Rect& crop,
                      const Ellipse& detected, FeatureWorkspace& ws,
                      std::vector<Eigen::Vector2d>& points, bool rimEdgeModel) {
  points.clear();
  // The crop was checked against the frame rethresholdCrop saw; reading another, smaller
  // frame through it would run past its rows.
  IMAGEPRO_EXPECTS(grey.empty() || (crop & cv::Rect(0, 0, grey.cols, grey.rows)) == crop,
                   "the crop lies inside the frame rethresholdCrop was given");
  if (grey.empty() || grey.type() != CV_8UC1 || ws.threshold < 0 || ws.crop != crop) return Status::EmptyFrame;
  const double band = contourBandPx(detected);
  if (mode == ContourMode::SubPixel) {
    // The grey frame itself, its binary crossing taken at the threshold on the fly.
    const EdgeLevels levels{ws.dark_mean, ws.bright_mean};
    ws.rim_crossings.clear();
    fullPathMod(ThresholdLines{grey, {0, 0, grey.cols, grey.rows}, ws.threshold}, crop, grey, detected, band, true,
                levels, points, &ws.rim_crossings, rimEdgeModel);
    ws.rim_blur_spread_px = 0.0;
    if (rimEdgeModel) {
      const RimEdgeFit fit = modelRimEdge(grey, detected, ws, points);
      if (fit.fitted) {
        const Eigen::Matrix2d& S = fit.blur_covariance;
        const double half = 0.5 * (S(0, 0) + S(1, 1));
        const double widest = half + std::hypot(0.5 * (S(0, 0) - S(1, 1)), S(0, 1));
        ws.rim_blur_spread_px = std::sqrt(std::max(widest, 0.0));
      }
    }
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

}  // namespace imagepro
