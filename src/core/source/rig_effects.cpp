#include "core/source/rig_effects.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace imagepro {

namespace {

constexpr double kClearOfSpotsMm = 1.0;
constexpr int kAttempts = 64;
// The polygon is filled on a grid this many times finer per axis, then averaged down.
constexpr int kSupersampling = 4;
constexpr int kShiftBits = 4;  // fillPoly's fixed-point fraction

Eigen::Vector2d direction(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

// The strip's outline in the target plane, its long edges subdivided so that the lens
// bends them as it bends any line.
std::vector<Eigen::Vector2d> stripOutline(const Occluder& o) {
  const Eigen::Vector2d along = (o.to - o.from).normalized();
  const Eigen::Vector2d side = Eigen::Vector2d(-along.y(), along.x()) * (0.5 * o.width_mm);
  const int n = 48;
  std::vector<Eigen::Vector2d> outline;
  outline.reserve(2 * (n + 1));
  for (int k = 0; k <= n; ++k) outline.push_back(o.from + (o.to - o.from) * (double(k) / n) + side);
  for (int k = n; k >= 0; --k) outline.push_back(o.from + (o.to - o.from) * (double(k) / n) - side);
  return outline;
}

std::vector<Eigen::Vector2d> circleOutline(const Eigen::Vector2d& centre, double radius) {
  const int n = 64;
  std::vector<Eigen::Vector2d> outline;
  outline.reserve(n);
  for (int k = 0; k < n; ++k) outline.push_back(centre + radius * direction(2.0 * M_PI * k / n));
  return outline;
}

// The fraction of each pixel of `box` that the target-plane polygon `outline` covers in the
// image (CV_32FC1, box-sized). `pad_px` grows the box beyond the polygon's image. False when
// a point lies behind the camera or the polygon misses the image.
bool polygonCoverage(const CameraModel& camera, const Pose& pose, const std::vector<Eigen::Vector2d>& outline,
                     int pad_px, cv::Rect& box, cv::Mat& coverage) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  std::vector<Eigen::Vector2d> image;
  image.reserve(outline.size());
  double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
  for (const Eigen::Vector2d& p : outline) {
    const Eigen::Vector3d P = R * Eigen::Vector3d(p.x(), p.y(), 0.0) + T;
    if (!(P.z() > 1.0)) return false;
    const Eigen::Vector2d q = distortPixel(camera, projectIdeal(camera, P));
    image.push_back(q);
    u0 = std::min(u0, q.x()), v0 = std::min(v0, q.y()), u1 = std::max(u1, q.x()), v1 = std::max(v1, q.y());
  }
  const cv::Rect frame(0, 0, camera.width, camera.height);
  const double limit = 4.0 * (camera.width + camera.height);  // far outside: clipped anyway
  u0 = std::max(u0, -limit), v0 = std::max(v0, -limit), u1 = std::min(u1, limit), v1 = std::min(v1, limit);
  box = cv::Rect(cv::Point(static_cast<int>(std::floor(u0)) - pad_px, static_cast<int>(std::floor(v0)) - pad_px),
                 cv::Point(static_cast<int>(std::ceil(u1)) + pad_px + 2, static_cast<int>(std::ceil(v1)) + pad_px + 2)) &
        frame;
  if (box.empty()) return false;
  // Pixel (u, v) covers [u - 0.5, u + 0.5): on the fine grid its samples start at
  // (u - 0.5 - box.x) * kSupersampling.
  const double scale = kSupersampling * double(1 << kShiftBits);
  std::vector<cv::Point> fine;
  fine.reserve(image.size());
  for (const Eigen::Vector2d& q : image) {
    const double x = std::clamp(q.x(), -limit, limit), y = std::clamp(q.y(), -limit, limit);
    fine.emplace_back(static_cast<int>(std::lround((x + 0.5 - box.x) * scale - 0.5 * (1 << kShiftBits))),
                      static_cast<int>(std::lround((y + 0.5 - box.y) * scale - 0.5 * (1 << kShiftBits))));
  }
  cv::Mat mask = cv::Mat::zeros(box.height * kSupersampling, box.width * kSupersampling, CV_8UC1);
  const cv::Point* points = fine.data();
  const int count = static_cast<int>(fine.size());
  cv::fillPoly(mask, &points, &count, 1, cv::Scalar(255), cv::LINE_8, kShiftBits);
  cv::Mat small;
  cv::resize(mask, small, box.size(), 0, 0, cv::INTER_AREA);
  small.convertTo(coverage, CV_32F, 1.0 / 255.0);
  return true;
}

}  // namespace

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

RigDraw drawRigEffects(const RigEffects& effects, const TargetGeometry& target, double card_size_mm,
                       SceneRandom& random) {
  RigDraw d;
  // The three choices first, so that each effect's share holds whatever the others draw.
  const bool occluded = random.uniform(0.0, 1.0) < effects.occluder_fraction;
  const bool glare = random.uniform(0.0, 1.0) < effects.glare_fraction;
  d.dim = random.uniform(0.0, 1.0) < effects.dim_fraction;
  d.dim_white = random.integer(70, 120);
  d.dim_black = random.integer(5, 20);

  const double R = target.radius_mm, r0 = target.spot_radius_mm;
  const std::array<Eigen::Vector2d, 2> spots{Eigen::Vector2d::Zero(), Eigen::Vector2d(target.spot_offset_mm, 0.0)};
  // Strips run 20 mm past the card's corners, out into the scene.
  const double reach = std::max(0.5 * std::sqrt(2.0) * card_size_mm, R) + 20.0;
  // The kind and the grey are drawn once; only where it lies is drawn again until it is clear
  // of the spots, so that tape (harder to place clear of them) keeps its share.
  const bool tape = random.uniform(0.0, 1.0) < 0.5;
  const int level = random.uniform(0.0, 1.0) < 0.5 ? random.integer(15, 60) : random.integer(70, 160);
  for (int attempt = 0; occluded && attempt < kAttempts; ++attempt) {
    Occluder o;
    o.present = true;
    o.width_mm = random.uniform(10.0, 25.0);
    o.level = level;
    if (tape) {  // across the disk: a chord strip
      const Eigen::Vector2d normal = direction(random.uniform(0.0, 2.0 * M_PI));
      const Eigen::Vector2d along(-normal.y(), normal.x());
      const double offset = random.uniform(-(R - 2.0), R - 2.0);
      const double half = std::sqrt(reach * reach - offset * offset);
      o.from = offset * normal - half * along;
      o.to = offset * normal + half * along;
    } else {  // a clamp or finger from outside, its tip inside the disk
      const double at = random.uniform(0.0, 2.0 * M_PI);
      const Eigen::Vector2d tip = random.uniform(0.55 * R, R - 2.0) * direction(at);
      const double turn = random.uniform(-M_PI / 3.0, M_PI / 3.0);
      o.from = tip;
      o.to = tip + (reach + R) * direction(at + turn);
    }
    bool clear = true;
    for (const Eigen::Vector2d& s : spots)
      clear = clear && distanceToSegment(s, o.from, o.to) >= 0.5 * o.width_mm + r0 + kClearOfSpotsMm;
    if (clear) {
      d.occluder = o;
      break;
    }
  }
  for (int attempt = 0; glare && attempt < kAttempts; ++attempt) {
    Glare g;
    g.present = true;
    g.diameter_mm = random.uniform(4.0, 12.0);
    const double most = R - 0.5 * g.diameter_mm - 1.0;
    g.centre = std::sqrt(random.uniform(0.0, 1.0)) * most * direction(random.uniform(0.0, 2.0 * M_PI));
    g.strength = random.uniform(1.2, 2.5) * 255.0;
    bool clear = true;
    for (const Eigen::Vector2d& s : spots)
      clear = clear && (g.centre - s).norm() >= 0.5 * g.diameter_mm + r0 + kClearOfSpotsMm;
    if (clear) {
      d.glare = g;
      break;
    }
  }
  return d;
}

void paintRigEffects(const RigDraw& draw, const CameraModel& camera, const Pose& pose, cv::Mat& scene) {
  CV_Assert(scene.type() == CV_32FC1 && scene.cols == camera.width && scene.rows == camera.height);
  cv::Rect box;
  cv::Mat coverage;
  if (draw.occluder.present && polygonCoverage(camera, pose, stripOutline(draw.occluder), 1, box, coverage)) {
    cv::Mat part = scene(box);
    cv::Mat keep = 1.0 - coverage;
    part = part.mul(keep) + coverage * static_cast<double>(draw.occluder.level);
  }
  if (draw.glare.present) {
    // The core is the glare's disk; its light spreads over a fifth of its image's size.
    const std::vector<Eigen::Vector2d> outline = circleOutline(draw.glare.centre, 0.5 * draw.glare.diameter_mm);
    if (polygonCoverage(camera, pose, outline, 0, box, coverage)) {
      const double sigma = std::max(0.5, 0.2 * 0.5 * (box.width + box.height));
      const int pad = static_cast<int>(std::ceil(3.0 * sigma));
      if (polygonCoverage(camera, pose, outline, pad, box, coverage)) {
        cv::GaussianBlur(coverage, coverage, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
        cv::Mat part = scene(box);
        part += coverage * draw.glare.strength;
      }
    }
  }
}

}  // namespace imagepro
