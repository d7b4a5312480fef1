#include "core/reconstruction/spot_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace imagepro {

namespace {

// The mean grey level of the 3 x 3 pixels about (x, y); a large value off the image.
double mean3x3(const cv::Mat& grey, int x, int y) {
  if (x < 1 || y < 1 || x >= grey.cols - 1 || y >= grey.rows - 1) return 1e9;
  int sum = 0;
  for (int dy = -1; dy <= 1; ++dy) {
    const std::uint8_t* row = grey.ptr<std::uint8_t>(y + dy);
    sum += row[x - 1] + row[x] + row[x + 1];
  }
  return sum / 9.0;
}

struct Darkest {
  double level = 1e9;
  int x = 0, y = 0;
  void consider(const cv::Mat& grey, int px, int py) {
    const double m = mean3x3(grey, px, py);
    if (m < level) {
      level = m;
      x = px;
      y = py;
    }
  }
};

cv::Rect boxAbout(int x, int y, int half) { return {x - half, y - half, 2 * half + 1, 2 * half + 1}; }

// A spot is a dark blob on the white disk: at least 12 of 16 points on a circle of
// `radius` about (x, y) must be brighter than `mid`. The darkest point of a dark region
// that only lies where a spot should (a hole in a ring, a dark patch) is no spot.
bool ringedByPaper(const cv::Mat& grey, int x, int y, double radius, double mid) {
  constexpr int kSamples = 16, kNeeded = 12;
  int bright = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double a = 2.0 * M_PI * i / kSamples;
    const int px = static_cast<int>(std::lround(x + radius * std::cos(a)));
    const int py = static_cast<int>(std::lround(y + radius * std::sin(a)));
    if (px >= 0 && py >= 0 && px < grey.cols && py < grey.rows && grey.ptr<std::uint8_t>(py)[px] > mid) ++bright;
  }
  return bright >= kNeeded;
}

}  // namespace

bool spotBoxesByModel(const cv::Mat& grey, const Ellipse& detected, const TargetGeometry& target, double bright,
                      double dark, std::array<cv::Rect, 2>& boxes) {
  if (grey.empty() || grey.type() != CV_8UC1 || !(detected.b > 0.0) || !(target.radius_mm > 0.0)) return false;
  const double contrast = bright - dark;
  if (!(contrast > 0.0)) return false;
  const double darkEnough = bright - 0.2 * contrast;
  const double spotPx = std::max(1.0, target.spot_radius_mm / target.radius_mm * detected.a);
  const int half = static_cast<int>(std::ceil(spotPx));

  // The centre spot: perspective moves it from the ellipse's centre by far less than this.
  Darkest centre;
  const int reach = static_cast<int>(std::ceil(std::max(2.0, 0.15 * detected.b)));
  const int cx = static_cast<int>(std::lround(detected.cx)), cy = static_cast<int>(std::lround(detected.cy));
  for (int y = cy - reach; y <= cy + reach; ++y)
    for (int x = cx - reach; x <= cx + reach; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= reach * reach) centre.consider(grey, x, y);
  if (!(centre.level <= darkEnough)) return false;

  // The offset spot: the darkest point of the scaled ellipse, at least two spot radii
  // from the centre spot, then the darkest pixel next to it.
  const double scale = target.spot_offset_mm / target.radius_mm;
  const double t = detected.angle_deg * M_PI / 180.0;
  const double ca = std::cos(t), sa = std::sin(t);
  const int samples = std::max(32, static_cast<int>(std::ceil(4.0 * M_PI * scale * detected.a)));
  Darkest offset;
  for (int i = 0; i < samples; ++i) {
    const double phi = 2.0 * M_PI * i / samples;
    const double ex = scale * detected.a * std::cos(phi), ey = scale * detected.b * std::sin(phi);
    const int x = static_cast<int>(std::lround(detected.cx + ca * ex - sa * ey));
    const int y = static_cast<int>(std::lround(detected.cy + sa * ex + ca * ey));
    if (std::hypot(x - centre.x, y - centre.y) < 2.0 * spotPx) continue;
    offset.consider(grey, x, y);
  }
  if (!(offset.level <= darkEnough)) return false;
  const int ox = offset.x, oy = offset.y;
  for (int y = oy - 1; y <= oy + 1; ++y)
    for (int x = ox - 1; x <= ox + 1; ++x) offset.consider(grey, x, y);

  // Paper round both: two spot radii and a pixel of blur out, short of the other spot.
  const double ring = 2.0 * spotPx + 1.0, mid = dark + 0.5 * contrast;
  if (!ringedByPaper(grey, centre.x, centre.y, ring, mid) || !ringedByPaper(grey, offset.x, offset.y, ring, mid))
    return false;

  boxes = {boxAbout(centre.x, centre.y, half), boxAbout(offset.x, offset.y, half)};
  return true;
}

}  // namespace imagepro
