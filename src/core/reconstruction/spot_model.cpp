#include "core/reconstruction/spot_model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/reconstruction/feature_geometry.h"

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

// A spot is a dark blob on the white disk, with paper round it: at least three quarters
// of the points on two circles about (x, y) (radii `inner` and `outer`, 16 points each)
// must be brighter than `mid`, and the spot's own level is judged against their median, the
// paper's level there (`paper`). The darkest point of a dark region that only lies where a
// spot should (a hole in a ring, a dark patch) is no spot. Only points on the disk count,
// clear of its blurred rim (`disk`: inside 1 of it) and of the other spot (nearer than
// `clear` to (ox, oy)): on a small, steeply seen target the circles reach past the disk's
// narrow sides into the card, and the two spots lie close. With fewer than 8 such points
// there is no telling, and no spot.
bool paperRound(const cv::Mat& grey, int x, int y, double inner, double outer, double mid,
                const feature_detail::EllipseForm& disk, int ox, int oy, double clear, double& paper) {
  constexpr int kPerCircle = 16, kFewest = 8;
  std::array<int, 2 * kPerCircle> levels{};
  int counted = 0, bright = 0;
  for (const double radius : {inner, outer}) {
    for (int i = 0; i < kPerCircle; ++i) {
      const double a = 2.0 * M_PI * (i + (radius == inner ? 0.0 : 0.5)) / kPerCircle;
      const int px = static_cast<int>(std::lround(x + radius * std::cos(a)));
      const int py = static_cast<int>(std::lround(y + radius * std::sin(a)));
      if (!(disk.rho2(px, py) < 1.0) || std::hypot(px - ox, py - oy) < clear) continue;
      if (px < 0 || py < 0 || px >= grey.cols || py >= grey.rows) continue;
      const int g = grey.ptr<std::uint8_t>(py)[px];
      levels[counted++] = g;
      if (g > mid) ++bright;
    }
  }
  if (counted < kFewest || 4 * bright < 3 * counted) return false;
  std::nth_element(levels.begin(), levels.begin() + counted / 2, levels.begin() + counted);
  paper = levels[counted / 2];
  return true;
}

}  // namespace

bool spotBoxesByModel(const cv::Mat& grey, const Ellipse& detected, const TargetGeometry& target, double bright,
                      double dark, std::array<cv::Rect, 2>& boxes) {
  if (grey.empty() || grey.type() != CV_8UC1 || !(detected.b > 0.0) || !(target.radius_mm > 0.0)) return false;
  const double contrast = bright - dark;
  if (!(contrast > 0.0)) return false;
  const double spotPx = std::max(1.0, target.spot_radius_mm / target.radius_mm * detected.a);
  const int half = static_cast<int>(std::ceil(spotPx));

  // The centre spot: perspective moves it from the ellipse's centre by far less than this.
  Darkest centre;
  const int reach = static_cast<int>(std::ceil(std::max(2.0, 0.15 * detected.b)));
  const int cx = static_cast<int>(std::lround(detected.cx)), cy = static_cast<int>(std::lround(detected.cy));
  for (int y = cy - reach; y <= cy + reach; ++y)
    for (int x = cx - reach; x <= cx + reach; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= reach * reach) centre.consider(grey, x, y);

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
  if (offset.level > 255.0) return false;  // no point of the scaled ellipse clear of the centre spot
  const int ox = offset.x, oy = offset.y;
  for (int y = oy - 1; y <= oy + 1; ++y)
    for (int x = ox - 1; x <= ox + 1; ++x) offset.consider(grey, x, y);

  // Paper round both, a pixel and a half of blur beyond one and one and a half spot radii,
  // on the disk two pixels in from its rim and a spot radius and two pixels clear of the
  // other spot; and each spot darker than that paper by a fifth of the paper-to-card
  // contrast. The paper's level is the spot's own: the crop's bright class mean takes in
  // the blurred rim, and the light falls off across the disk.
  const double inner = spotPx + 1.5, outer = 1.5 * spotPx + 1.5, mid = dark + 0.5 * contrast, clear = spotPx + 2.0;
  const feature_detail::EllipseForm disk(detected, std::max(0.0, 1.0 - 2.0 / detected.b));
  auto isSpot = [&](const Darkest& spot, const Darkest& other) {
    double paper = 0.0;
    return paperRound(grey, spot.x, spot.y, inner, outer, mid, disk, other.x, other.y, clear, paper) &&
           spot.level <= paper - 0.2 * (paper - dark);
  };
  if (!isSpot(centre, offset) || !isSpot(offset, centre)) return false;

  boxes = {boxAbout(centre.x, centre.y, half), boxAbout(offset.x, offset.y, half)};
  return true;
}

}  // namespace imagepro
