#include "core/tracking/tracker.h"

#include <algorithm>
#include <cmath>

#include "core/tracking/polynomial.h"

namespace imagepro {

namespace {

// How far a target may move in a frame before two detections tell it, in box sizes.
constexpr double kUnknownMotionPerBoxSize = 0.25;

constexpr int kRimSamples = 48;

// Brings an angle to within 180 degrees of `reference`, so angle series stay continuous.
double unwrapNear(double angle, double reference) {
  while (angle - reference > 180.0) angle -= 360.0;
  while (angle - reference < -180.0) angle += 360.0;
  return angle;
}

}  // namespace

cv::Rect2d projectedTargetBox(const CameraModel& camera, const TargetGeometry& target, const Pose& pose) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
  for (int i = 0; i < kRimSamples; ++i) {
    const double a = 2.0 * M_PI * i / kRimSamples;
    const Eigen::Vector3d P = R * Eigen::Vector3d(target.radius_mm * std::cos(a), target.radius_mm * std::sin(a), 0) + T;
    if (P.z() <= 1e-6) return {};  // behind the camera: no box
    const Eigen::Vector2d uv = distortPixel(camera, projectIdeal(camera, P));
    u0 = std::min(u0, uv.x());
    v0 = std::min(v0, uv.y());
    u1 = std::max(u1, uv.x());
    v1 = std::max(v1, uv.y());
  }
  return {u0, v0, u1 - u0, v1 - v0};
}

cv::Rect2d enlargeRegion(const cv::Rect2d& box, const TrackingOptions& o, double speed) {
  const double grow = o.enlarge_scale + o.enlarge_speed_scale * std::max(0.0, speed);
  const double dw = o.enlarge_px + grow * box.width;
  const double dh = o.enlarge_px + grow * box.height;
  return {box.x - dw / 2, box.y - dh / 2, box.width + dw, box.height + dh};
}

void RegionTracker::reset() {
  count_ = 0;
  head_ = 0;
  active_points_ = 0;
  active_degree_ = 0;
  last_r_ = 1.0;
  last_region_.reset();
  last_box_.reset();
}

const RegionTracker::Sample& RegionTracker::fromNewest(std::size_t k) const {
  return ring_[(head_ + kHistory - 1 - k) % kHistory];
}

void RegionTracker::observe(double t, const cv::Rect2d& box, const std::optional<Pose>& pose) {
  Sample s;
  s.t = t;
  s.corners = {box.x, box.y, box.x + box.width, box.y + box.height};
  if (pose) {
    s.has_pose = true;
    s.pose = {pose->rx_deg, pose->ry_deg, pose->rz_deg, pose->tx_mm, pose->ty_mm, pose->tz_mm};
    if (count_ > 0 && fromNewest(0).has_pose)
      for (int i = 0; i < 3; ++i) s.pose[i] = unwrapNear(s.pose[i], fromNewest(0).pose[i]);
  }
  ring_[head_] = s;
  head_ = (head_ + 1) % kHistory;
  count_ = std::min<std::size_t>(count_ + 1, kHistory);
  // One more point and one more degree per observation, up to what is asked (3.3.1).
  active_points_ = std::min(active_points_ + 1, kHistory);
  active_degree_ = std::min(active_degree_ + 1, 3);
}

std::optional<cv::Rect> RegionTracker::estimate(const TrackingOptions& o, const CameraModel& camera,
                                                const TargetGeometry& target, double t, cv::Size image) {
  // One detection tells where the target was, not where it goes: the region about it is a
  // guess (degree 0, no speed), which the engine backs with the whole frame when it misses.
  if (o.mode == TrackingMode::Off || count_ < 1) return std::nullopt;
  const bool use3d = o.mode == TrackingMode::Parameters3D;
  if (use3d && !fromNewest(0).has_pose) return std::nullopt;

  int n = std::min({active_points_, o.data_points, static_cast<int>(count_)});
  int degree = std::min({active_degree_, o.degree, n - 1});
  if (use3d) {  // only samples with a pose count
    int with_pose = 0;
    while (with_pose < n && fromNewest(static_cast<std::size_t>(with_pose)).has_pose) ++with_pose;
    n = with_pose;
    degree = std::min(degree, n - 1);
  }

  std::array<double, kHistory> ts{}, xs{};
  const std::size_t values = use3d ? 6 : 4;
  auto fit = [&](int points, int deg, std::array<double, 6>& est) {
    double min_r = 1.0;
    for (std::size_t v = 0; v < values; ++v) {
      for (int i = 0; i < points; ++i) {
        const Sample& s = fromNewest(static_cast<std::size_t>(points - 1 - i));  // oldest first
        ts[i] = s.t;
        xs[i] = use3d ? s.pose[v] : s.corners[v];
      }
      const Extrapolation e = extrapolatePolynomial({ts.data(), static_cast<std::size_t>(points)},
                                                    {xs.data(), static_cast<std::size_t>(points)}, deg, t);
      est[v] = e.estimate;
      min_r = std::min(min_r, e.r);
    }
    return min_r;
  };

  std::array<double, 6> est{};
  last_r_ = fit(n, degree, est);
  // A constant (degree 0) fit explains none of the variance, so its r is always 0:
  // the rule only applies to fits of degree 1 and up.
  if (degree >= 1 && last_r_ < o.min_r && n > 2) {
    // The motion changed: degree 1 over the last two samples, then grow back (3.3.1).
    active_points_ = 2;
    active_degree_ = 1;
    n = 2;
    degree = 1;
    fit(n, degree, est);
  }

  cv::Rect2d box;
  if (use3d) {
    const Pose p{est[0], est[1], est[2], est[3], est[4], est[5]};
    box = projectedTargetBox(camera, target, p);
  } else {
    box = {est[0], est[1], est[2] - est[0], est[3] - est[1]};
  }
  if (!(box.width > 0 && box.height > 0)) return std::nullopt;
  last_box_ = box;

  // Speed of the box centre over the last two detections, pixels per frame.
  double speed = 0.0;
  if (count_ >= 2) {
    const auto& a = fromNewest(0).corners;
    const auto& b = fromNewest(1).corners;
    speed = 0.5 * std::hypot(a[0] + a[2] - b[0] - b[2], a[1] + a[3] - b[1] - b[3]);
  }
  cv::Rect2d region = enlargeRegion(box, o, speed);
  if (count_ == 1) {
    // From one detection the speed is not known: the region also reaches as far as the
    // target could move in a frame, taken as a quarter of its box (the tracking study's
    // fastest motion, the pendulum, moves its box by about a seventh).
    const double dx = kUnknownMotionPerBoxSize * box.width, dy = kUnknownMotionPerBoxSize * box.height;
    region = {region.x - dx, region.y - dy, region.width + 2 * dx, region.height + 2 * dy};
  }

  // Damp shrinking: neither side may shrink by more than red % per frame (3.3.3).
  if (last_region_) {
    const double keep = 1.0 - o.reduction_percent / 100.0;
    const double min_w = last_region_->width * keep;
    const double min_h = last_region_->height * keep;
    if (region.width < min_w) {
      region.x -= (min_w - region.width) / 2;
      region.width = min_w;
    }
    if (region.height < min_h) {
      region.y -= (min_h - region.height) / 2;
      region.height = min_h;
    }
  }
  last_region_ = region;

  const cv::Rect whole(0, 0, image.width, image.height);
  // Round outwards, ignoring floating-point dust on whole pixel values.
  constexpr double kDust = 1e-6;
  const cv::Point tl(static_cast<int>(std::floor(region.x + kDust)), static_cast<int>(std::floor(region.y + kDust)));
  const cv::Point br(static_cast<int>(std::ceil(region.x + region.width - kDust)),
                     static_cast<int>(std::ceil(region.y + region.height - kDust)));
  const cv::Rect r = cv::Rect(tl, br) & whole;
  if (r.width < 8 || r.height < 8) return std::nullopt;
  return r;
}

}  // namespace imagepro
