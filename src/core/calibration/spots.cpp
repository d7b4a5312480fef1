#include "core/calibration/spots.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "core/segmentation/threshold.h"

namespace imagepro {
namespace {

constexpr int kWeightRingPx = kSpotClearancePx - 1;  // the rim's blur and anti-aliasing reach this far out

bool nearComponent(const cv::Mat& labels, int label, int x, int y) {
  const int x0 = std::max(x - kWeightRingPx, 0), x1 = std::min(x + kWeightRingPx, labels.cols - 1);
  const int y0 = std::max(y - kWeightRingPx, 0), y1 = std::min(y + kWeightRingPx, labels.rows - 1);
  for (int yy = y0; yy <= y1; ++yy) {
    const int* row = labels.ptr<int>(yy);
    for (int xx = x0; xx <= x1; ++xx)
      if (row[xx] == label) return true;
  }
  return false;
}

// Median grey on the border of `box` (clipped to the image), over pixels of no component;
// false when there is none.
bool whiteLevel(const cv::Mat& grey, const cv::Mat& labels, cv::Rect box, std::vector<unsigned char>& border,
                double& white) {
  border.clear();
  const cv::Rect image(0, 0, grey.cols, grey.rows);
  auto take = [&](int x, int y) {
    if (image.contains({x, y}) && labels.at<int>(y, x) == 0) border.push_back(grey.at<unsigned char>(y, x));
  };
  const int x1 = box.x + box.width - 1, y1 = box.y + box.height - 1;
  for (int x = box.x; x <= x1; ++x) {
    take(x, box.y);
    take(x, y1);
  }
  for (int y = box.y + 1; y < y1; ++y) {
    take(box.x, y);
    take(x1, y);
  }
  if (border.empty()) return false;
  auto mid = border.begin() + static_cast<std::ptrdiff_t>(border.size() / 2);
  std::nth_element(border.begin(), mid, border.end());
  white = *mid;
  return true;
}

bool touchesOtherComponent(const cv::Mat& labels, int label, cv::Rect box) {
  box &= cv::Rect(0, 0, labels.cols, labels.rows);
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = box.x; x < box.x + box.width; ++x)
      if (row[x] != 0 && row[x] != label) return true;
  }
  return false;
}

// Halfway between the mean grey levels of [0, t] and [t+1, 255].
int midClassThreshold(const Histogram& h, int t) {
  double n1 = 0, s1 = 0, n2 = 0, s2 = 0;
  for (int g = 0; g < 256; ++g) {
    if (g <= t) {
      n1 += h[g];
      s1 += static_cast<double>(g) * h[g];
    } else {
      n2 += h[g];
      s2 += static_cast<double>(g) * h[g];
    }
  }
  if (n1 == 0 || n2 == 0) return t;
  return static_cast<int>(std::floor(0.5 * (s1 / n1 + s2 / n2)));
}

}  // namespace

Status findPatternSpots(const cv::Mat& grey, const ThresholdOptions& threshold, SpotFinderWorkspace& ws,
                        std::vector<ObservedSpot>& out) {
  return findPatternSpots(grey, grey, threshold, ws, out);
}

Status findPatternSpots(const cv::Mat& segment, const cv::Mat& grey, const ThresholdOptions& threshold,
                        SpotFinderWorkspace& ws, std::vector<ObservedSpot>& out, double max_area_fraction) {
  out.clear();
  if (grey.empty() || grey.type() != CV_8UC1 || segment.size() != grey.size() || segment.type() != CV_8UC1)
    return Status::EmptyFrame;
  computeHistogram(segment, ws.histogram);
  ThresholdOptions o = threshold;
  if (o.method == ThresholdMethod::None) o.method = ThresholdMethod::AtMod;
  int t = 0;
  if (const Status s = computeThreshold(o, ws.histogram, t); !ok(s)) return s;
  if (o.method != ThresholdMethod::Manual) t = midClassThreshold(ws.histogram, t);
  cv::compare(segment, t, ws.dark, cv::CMP_LE);
  const int n = cv::connectedComponentsWithStats(ws.dark, ws.labels, ws.stats, ws.centroids, 8, CV_32S);
  const int maxArea = static_cast<int>(max_area_fraction * grey.rows * grey.cols);
  for (int label = 1; label < n; ++label) {
    const int* st = ws.stats.ptr<int>(label);
    const cv::Rect box(st[cv::CC_STAT_LEFT], st[cv::CC_STAT_TOP], st[cv::CC_STAT_WIDTH], st[cv::CC_STAT_HEIGHT]);
    const int area = st[cv::CC_STAT_AREA];
    if (area < kMinSpotAreaPx || area > maxArea) continue;
    if (box.x == 0 || box.y == 0 || box.x + box.width == grey.cols || box.y + box.height == grey.rows) continue;

    const cv::Rect clearBox(box.x - kSpotClearancePx, box.y - kSpotClearancePx, box.width + 2 * kSpotClearancePx,
                            box.height + 2 * kSpotClearancePx);
    // Anything else dark this close would lend its blurred rim to the weights.
    if (touchesOtherComponent(ws.labels, label, clearBox)) continue;
    double white = 0.0;
    if (!whiteLevel(grey, ws.labels, clearBox, ws.border, white)) continue;
    const cv::Rect weightBox =
        cv::Rect(box.x - kWeightRingPx, box.y - kWeightRingPx, box.width + 2 * kWeightRingPx,
                 box.height + 2 * kWeightRingPx) &
        cv::Rect(0, 0, grey.cols, grey.rows);
    double sw = 0.0, sx = 0.0, sy = 0.0;
    for (int y = weightBox.y; y < weightBox.y + weightBox.height; ++y) {
      const unsigned char* g = grey.ptr<unsigned char>(y);
      const int* lab = ws.labels.ptr<int>(y);
      for (int x = weightBox.x; x < weightBox.x + weightBox.width; ++x) {
        if (lab[x] != label && (lab[x] != 0 || !nearComponent(ws.labels, label, x, y))) continue;
        const double w = white - g[x];
        if (w <= 0.0) continue;
        sw += w;
        sx += w * x;
        sy += w * y;
      }
    }
    if (!(sw > 0.0)) continue;
    out.push_back({Eigen::Vector2d(sx / sw, sy / sw), area});
  }
  return Status::Ok;
}

}  // namespace imagepro
