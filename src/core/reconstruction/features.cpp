#include "core/reconstruction/features.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/segmentation/threshold.h"

namespace imagepro {

namespace {

constexpr double kSpotSearchScale = 0.85;  // spots are searched inside 0.85 of the rim
constexpr int kSpotBoxGrowPx = 3;
constexpr double kSpotRimClearancePx = 2.5;  // spot centroids ignore pixels this near the rim
constexpr double kRaySteps = 16.0;  // 8 points MOD: samples per pixel along a ray
constexpr double kMinSubPixelContrastFraction = 0.3;

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

// Grey levels along one image row or column, with linear interpolation in between.
struct GreyLine {
  const cv::Mat& grey;
  bool alongRow;  // true: varies u along row `fixed`; false: varies v along column `fixed`
  int fixed;
  int length() const { return alongRow ? grey.cols : grey.rows; }
  double at(int k) const {
    return alongRow ? grey.ptr<std::uint8_t>(fixed)[k] : grey.ptr<std::uint8_t>(k)[fixed];
  }
  bool interp(double x, double& value) const {
    const int k = static_cast<int>(std::floor(x));
    if (k < 0 || k + 1 >= length()) return false;
    const double f = x - k;
    value = (1.0 - f) * at(k) + f * at(k + 1);
    return true;
  }
};

// Moves a rim crossing x0 on a grey line to where the grey level crosses the mean of its
// two plateaus, sampled 2.5 and 3.5 px either side; `in` is +1 or -1, towards white. The
// binary crossing can lie a pixel or two off the mid-level (a threshold near one class
// under blur), so the plateaus are re-centred on each new crossing until it settles.
bool refineCrossing(const GreyLine& line, int in, double minContrast, double& x0) {
  constexpr int kMaxPasses = 4;
  constexpr int kSearchPx = 3;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    double o1, o2, i1, i2;
    if (!line.interp(x0 - in * 2.5, o1) || !line.interp(x0 - in * 3.5, o2) ||
        !line.interp(x0 + in * 2.5, i1) || !line.interp(x0 + in * 3.5, i2))
      return false;
    const double outside = 0.5 * (o1 + o2), inside = 0.5 * (i1 + i2);
    if (!(inside - outside >= minContrast)) return false;
    const double level = 0.5 * (inside + outside);
    const int k0 = static_cast<int>(std::floor(x0));
    double best = 0.0;
    bool found = false;
    for (int k = std::max(k0 - kSearchPx, 0); k <= std::min(k0 + kSearchPx, line.length() - 2); ++k) {
      const double g0 = line.at(k), g1 = line.at(k + 1);
      // Only a rise towards white counts.
      if ((g1 - g0) * in <= 0.0 || (g0 - level) * (g1 - level) > 0.0) continue;
      const double x = k + (level - g0) / (g1 - g0);
      if (!found || std::abs(x - x0) < std::abs(best - x0)) best = x;
      found = true;
    }
    if (!found) return false;
    const double moved = std::abs(best - x0);
    x0 = best;
    if (moved < 0.02) break;
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

void fullPathOrg(const BinaryView& view, FeatureWorkspace& ws, std::vector<Eigen::Vector2d>& out) {
  const cv::Rect& c = view.crop;
  ws.visited.create(c.height, c.width, CV_8UC1);
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
  const int x0 = static_cast<int>(std::lround(detected.cx));
  const int y0 = static_cast<int>(std::lround(detected.cy));
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
      return view.white(static_cast<int>(std::lround(detected.cx + t * ux)),
                        static_cast<int>(std::lround(detected.cy + t * uy)));
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

void fullPathMod(const BinaryView& view, const cv::Mat& grey, const Ellipse& detected,
                 double band, bool subPixel, double minContrast,
                 std::vector<Eigen::Vector2d>& out) {
  const EllipseForm form(detected, 1.0);
  const cv::Rect& c = view.crop;
  // Rows cross the parts of the rim whose normal is closer to horizontal.
  for (int y = c.y; y < c.y + c.height; ++y) {
    double xs[2];
    if (!form.rowCrossings(y, xs[0], xs[1])) continue;
    for (int side = 0; side < 2; ++side) {
      const double xe = xs[side];
      if (!form.normalMostlyHorizontal(xe, y)) continue;
      const int in = side == 0 ? 1 : -1;
      const int start = static_cast<int>(std::lround(xe - in * band));
      const int end = static_cast<int>(std::lround(xe + in * band));
      const int k = firstRimPixel(start, end, in, [&](int x) { return view.white(x, y); });
      // SubPixel starts from the detected rim where the binary crop shows no crossing
      // (a threshold close to the white level under blur can leave none within the band).
      if (k == INT32_MIN && !subPixel) continue;
      double x = k == INT32_MIN ? xe : k - in * 0.5;
      if (subPixel && !refineCrossing(GreyLine{grey, true, y}, in, minContrast, x)) continue;
      out.emplace_back(x, y);
    }
  }
  // Columns cross the rest.
  for (int x = c.x; x < c.x + c.width; ++x) {
    double ys[2];
    if (!form.columnCrossings(x, ys[0], ys[1])) continue;
    for (int side = 0; side < 2; ++side) {
      const double ye = ys[side];
      if (form.normalMostlyHorizontal(x, ye)) continue;
      const int in = side == 0 ? 1 : -1;
      const int start = static_cast<int>(std::lround(ye - in * band));
      const int end = static_cast<int>(std::lround(ye + in * band));
      const int k = firstRimPixel(start, end, in, [&](int v) { return view.white(x, v); });
      // SubPixel starts from the detected rim where the binary crop shows no crossing
      // (a threshold close to the white level under blur can leave none within the band).
      if (k == INT32_MIN && !subPixel) continue;
      double y = k == INT32_MIN ? ye : k - in * 0.5;
      if (subPixel && !refineCrossing(GreyLine{grey, false, x}, in, minContrast, y)) continue;
      out.emplace_back(x, y);
    }
  }
}

// Mean grey level of the classes [0, t] and [t+1, 255] of a histogram.
void classMeans(const Histogram& h, int t, double& dark, double& bright) {
  double n0 = 0, s0 = 0, n1 = 0, s1 = 0;
  for (int g = 0; g < 256; ++g) {
    if (g <= t) {
      n0 += h[g];
      s0 += static_cast<double>(g) * h[g];
    } else {
      n1 += h[g];
      s1 += static_cast<double>(g) * h[g];
    }
  }
  dark = n0 > 0 ? s0 / n0 : 0.0;
  bright = n1 > 0 ? s1 / n1 : 255.0;
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
                       int frameThreshold, FeatureWorkspace& ws, int& threshold) {
  if (grey.empty() || grey.type() != CV_8UC1) return Status::EmptyFrame;
  if ((crop & cv::Rect(0, 0, grey.cols, grey.rows)) != crop || crop.area() == 0)
    return Status::OutOfImage;
  const cv::Mat region = grey(crop);
  computeHistogram(region, ws.histogram);
  if (rethreshold.method == ThresholdMethod::None) {
    if (frameThreshold < 0 || frameThreshold > 255) return Status::InvalidSettings;
    threshold = frameThreshold;
  } else if (const Status s = computeThreshold(rethreshold, ws.histogram, threshold); !ok(s)) {
    return s;
  }
  binarize(region, threshold, ws.binary);
  ws.threshold = threshold;
  return Status::Ok;
}

Status extractContour(ContourMode mode, const cv::Mat& grey, const cv::Rect& crop,
                      const Ellipse& detected, FeatureWorkspace& ws,
                      std::vector<Eigen::Vector2d>& points) {
  points.clear();
  if (ws.binary.rows != crop.height || ws.binary.cols != crop.width) return Status::EmptyFrame;
  const BinaryView view{ws.binary, crop};
  const double band = contourBandPx(detected);
  switch (mode) {
    case ContourMode::EightPointsOrg: eightPointsOrg(view, detected, points); break;
    case ContourMode::EightPointsMod: eightPointsMod(view, detected, band, points); break;
    case ContourMode::FullPathOrg: fullPathOrg(view, ws, points); break;
    case ContourMode::FullPathMod:
      fullPathMod(view, grey, detected, band, false, 0.0, points);
      break;
    case ContourMode::SubPixel: {
      // An edge must rise by a fair part of the crop's contrast to be refined.
      double dark = 0.0, bright = 255.0;
      classMeans(ws.histogram, ws.threshold, dark, bright);
      fullPathMod(view, grey, detected, band, true,
                  kMinSubPixelContrastFraction * std::max(bright - dark, 1.0), points);
      break;
    }
  }
  return points.size() >= 6 ? Status::Ok : Status::TooFewPoints;
}

Status extractSpots(const cv::Mat& grey, const cv::Rect& crop, const Ellipse& detected,
                    const TargetGeometry& target, FeatureWorkspace& ws, SpotFeatures& spots) {
  spots.candidates = 0;
  if (ws.binary.rows != crop.height || ws.binary.cols != crop.width) return Status::EmptyFrame;
  const EllipseForm inner(detected, kSpotSearchScale);
  // Spots are cut at the middle of the crop's two class means rather than at the threshold
  // itself: a minimum-error threshold near one class's level (as under blur) would swell
  // or shrink them, and merge two spots seen close together.
  double dark = 0.0, bright = 255.0;
  classMeans(ws.histogram, ws.threshold, dark, bright);
  const int spotLevel = static_cast<int>(std::floor(0.5 * (dark + bright)));
  std::vector<SpotRun>& runs = ws.runs;
  runs.clear();
  // Black runs inside the search ellipse, row by row; each run is joined to the
  // 8-connected runs of the row above.
  std::size_t prevBegin = 0, prevEnd = 0;
  for (int r = 0; r < crop.height; ++r) {
    const int y = crop.y + r;
    double xl, xr;
    const std::size_t rowBegin = runs.size();
    if (inner.rowCrossings(y, xl, xr)) {
      const int x0 = std::max(static_cast<int>(std::ceil(xl)), crop.x) - crop.x;
      const int x1 = std::min(static_cast<int>(std::floor(xr)), crop.x + crop.width - 1) - crop.x;
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y) + crop.x;
      for (int x = x0; x <= x1;) {
        if (row[x] > spotLevel) {
          ++x;
          continue;
        }
        const int start = x;
        while (x <= x1 && row[x] <= spotLevel) ++x;
        const int id = static_cast<int>(runs.size());
        runs.push_back({r, start, x - 1, id});
        for (std::size_t p = prevBegin; p < prevEnd; ++p) {
          if (runs[p].x0 <= x && runs[p].x1 >= start - 1) {
            const int a = findRoot(runs, static_cast<int>(p)), b = findRoot(runs, id);
            if (a != b) runs[std::max(a, b)].parent = std::min(a, b);
          }
        }
      }
    }
    prevBegin = rowBegin;
    prevEnd = runs.size();
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
  if (accepted < 2) return Status::SpotsNotFound;
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
    // The local white level: the box's border pixels inside the rim.
    double borderSum = 0.0;
    int borderCount = 0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      const bool edgeRow = y == box.y || y == box.y + box.height - 1;
      for (int x = box.x; x < box.x + box.width; x += edgeRow ? 1 : std::max(box.width - 1, 1)) {
        if (rim.rho2(x, y) >= rho2Max) continue;
        borderSum += row[x];
        ++borderCount;
      }
    }
    const double white = borderCount > 0 ? borderSum / borderCount : bright;
    double sw = 0.0, sx = 0.0, sy = 0.0;
    for (int y = box.y; y < box.y + box.height; ++y) {
      const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
      for (int x = box.x; x < box.x + box.width; ++x) {
        if (rim.rho2(x, y) >= rho2Max) continue;
        const double w = white - row[x];
        sw += w;
        sx += w * x;
        sy += w * y;
      }
    }
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
