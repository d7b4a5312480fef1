#include "core/calibration/intrinsics_report.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

namespace imagepro {
namespace {

std::string percent(double f) {
  char buf[24];
  std::snprintf(buf, sizeof buf, f < 0.1 ? "%.2f %%" : "%.0f %%", 100.0 * f);
  return buf;
}

}  // namespace

CoverageMap coverageMap(const IntrinsicsResult& r) {
  CoverageMap m;
  m.views.assign(kCoverageColumns * kCoverageRows, 0);
  if (r.width <= 0 || r.height <= 0) return m;
  for (const IntrinsicsView& v : r.views) {
    if (!ok(v.status)) continue;
    std::set<int> cells;
    for (const FoundDot& d : v.found) {
      const int cx = std::clamp(static_cast<int>(d.image_px.x() * kCoverageColumns / r.width), 0, kCoverageColumns - 1);
      const int cy = std::clamp(static_cast<int>(d.image_px.y() * kCoverageRows / r.height), 0, kCoverageRows - 1);
      cells.insert(cy * kCoverageColumns + cx);
    }
    for (const int c : cells) ++m.views[c];
  }
  int covered = 0, border = 0, borderCovered = 0;
  for (int y = 0; y < kCoverageRows; ++y)
    for (int x = 0; x < kCoverageColumns; ++x) {
      const bool has = m.views[y * kCoverageColumns + x] > 0;
      covered += has;
      if (x == 0 || y == 0 || x == kCoverageColumns - 1 || y == kCoverageRows - 1) {
        ++border;
        borderCovered += has;
      }
    }
  m.covered_fraction = static_cast<double>(covered) / (kCoverageColumns * kCoverageRows);
  m.border_fraction = static_cast<double>(borderCovered) / border;
  return m;
}

std::string coverageText(const CoverageMap& m) {
  std::string s;
  for (int y = 0; y < kCoverageRows; ++y) {
    for (int x = 0; x < kCoverageColumns; ++x) {
      const int n = m.views.empty() ? 0 : m.views[y * kCoverageColumns + x];
      s += n == 0 ? '.' : static_cast<char>('0' + std::min(n, 9));
      if (x + 1 < kCoverageColumns) s += ' ';
    }
    s += '\n';
  }
  return s;
}

cv::Mat coverageImage(const IntrinsicsResult& r, const CoverageMap& m) {
  const int w = std::max(r.width, 1), h = std::max(r.height, 1);
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(40, 40, 40));
  int maxViews = 1;
  for (const int n : m.views) maxViews = std::max(maxViews, n);
  for (int y = 0; y < kCoverageRows; ++y)
    for (int x = 0; x < kCoverageColumns; ++x) {
      const int n = m.views.empty() ? 0 : m.views[y * kCoverageColumns + x];
      const cv::Rect cell(x * w / kCoverageColumns, y * h / kCoverageRows, w / kCoverageColumns, h / kCoverageRows);
      // Uncovered cells dark red, covered ones greener with more views.
      const cv::Scalar colour = n == 0 ? cv::Scalar(30, 30, 110) : cv::Scalar(40, 60 + 120 * n / maxViews, 40);
      cv::rectangle(img, cell, colour, cv::FILLED);
      cv::rectangle(img, cell, cv::Scalar(90, 90, 90), 1);
    }
  int index = 0;
  for (const IntrinsicsView& v : r.views) {
    if (!ok(v.status)) continue;
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((index++ * 37) % 180, 200, 255)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
    for (const FoundDot& d : v.found)
      cv::circle(img, cv::Point(static_cast<int>(std::lround(d.image_px.x())), static_cast<int>(std::lround(d.image_px.y()))),
                 2, cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
  }
  return img;
}

std::vector<CalibrationWarning> intrinsicsWarnings(const IntrinsicsResult& r, const CoverageMap& m) {
  std::vector<CalibrationWarning> w;
  if (!ok(r.status)) return w;
  if (m.covered_fraction < kMinCoveredFraction)
    w.push_back({"PoorCoverage", "the dots fell in only " + percent(m.covered_fraction) +
                                     " of the image (coverage map): add views with the pattern in the empty parts, "
                                     "so the lens is measured where it will be used"});
  if (m.border_fraction < kMinBorderFraction)
    w.push_back({"PoorBorderCoverage", "only " + percent(m.border_fraction) +
                                           " of the image's border cells hold dots: the distortion there is "
                                           "extrapolated; add views with the pattern near each edge and corner"});
  double steepest = 0;
  for (const IntrinsicsView& v : r.views)
    if (ok(v.status)) steepest = std::max(steepest, v.tilt_deg);
  if (steepest < kMinSteepestTiltDeg)
    w.push_back({"NarrowViewAngles", "no view is tilted by more than " + std::to_string(static_cast<int>(steepest)) +
                                         " deg: the focal length is poorly separated from the distance; add views "
                                         "with the pattern turned 30-50 deg"});
  // Tilt axes: the normals' image-plane directions of the tilted views, as lines (mod 180
  // deg); their spread is 180 deg less the widest gap between neighbours.
  std::vector<double> axes;
  for (const IntrinsicsView& v : r.views)
    if (ok(v.status) && v.tilt_deg > 10.0) axes.push_back(std::fmod(std::atan2(v.tilt_axis.y(), v.tilt_axis.x()) * 180.0 / M_PI + 360.0, 180.0));
  std::sort(axes.begin(), axes.end());
  if (axes.size() >= 2) {
    double gap = axes.front() + 180.0 - axes.back();
    for (size_t i = 1; i < axes.size(); ++i) gap = std::max(gap, axes[i] - axes[i - 1]);
    if (180.0 - gap < 30.0)
      w.push_back({"OneTiltAxis", "every tilted view turns the pattern about the same axis: add views turned about "
                                  "the other (left-right as well as up-down)"});
  }
  if (r.views_used < kRecommendedViews)
    w.push_back({"FewViews", std::to_string(r.views_used) + " views used: 4 to 10 views, tilted differently, "
                                                           "determine the intrinsics better"});
  if (r.rms_px > kMaxGoodRmsPx)
    w.push_back({"HighReprojectionError", "the dots lie " + std::to_string(r.rms_px).substr(0, 5) +
                                              " px RMS from the model: check the per-image errors and drop blurred "
                                              "views or a pattern that is not flat"});
  if (r.fx > 0 && r.deviation.fx / r.fx > kMaxFocalDeviation)
    w.push_back({"UncertainFocalLength", "the focal length's standard deviation is " +
                                             percent(r.deviation.fx / r.fx) +
                                             ": add views, tilted more strongly and filling more of the image"});
  return w;
}

}  // namespace imagepro
