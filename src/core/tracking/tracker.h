#pragma once
// Target tracking (thesis chapter 3): estimates the region of the next frame in
// which to search for the target, from the targets found in the previous frames.
//  * 2D corners (3.2.2.1): four polynomials over the upper-left and lower-right
//    corners of the target's bounding box;
//  * 3D parameters (3.2.2.2): six polynomials over the pose, the estimated pose
//    projected through the camera to get the box.
// When a fit's correlation coefficient drops below min_r, the fit falls back to
// degree 1 over the last 2 samples and grows back one step per frame (3.3.1).
// The box is then enlarged by fixed pixels, a fixed scale and a scale proportional
// to the centre's speed, and its shrinking is damped by the reduction ratio (3.3.3).
// A missed frame clears the history: the next frame searches the whole image.
#include <opencv2/core.hpp>

#include <array>
#include <optional>

#include "core/common/geometry.h"
#include "core/settings/options.h"

namespace imagepro {

// Bounding box of the projected target disk (rim sampled, lens distortion applied).
cv::Rect2d projectedTargetBox(const CameraModel& camera, const TargetGeometry& target, const Pose& pose);

// Grows `box` by the three enlargements of thesis 3.3.3 (width and height each grow by
// enlarge_px + enlarge_scale*size + enlarge_speed_scale*speed*size, centred), where
// `speed_px_per_frame` is the target centre's image speed.
cv::Rect2d enlargeRegion(const cv::Rect2d& box, const TrackingOptions& options, double speed_px_per_frame);

class RegionTracker {
 public:
  static constexpr int kHistory = 100;

  void reset();
  // The target was found at time t with this bounding box (and pose when reconstructed).
  void observe(double t, const cv::Rect2d& box, const std::optional<Pose>& pose);
  // The target was not found: tracking restarts from the next detection.
  void observeMiss() { reset(); }

  // Region to search at time t, clipped to the image; nullopt means the whole image
  // (tracking off, no detection yet, or the estimate left the image). From a single
  // detection the region is that detection's box enlarged as usual and by a quarter of its
  // size on every side (how far it may move in a frame is not known yet): a guess
  // the caller should back with the whole image when it misses (fromOneDetection).
  std::optional<cv::Rect> estimate(const TrackingOptions& options, const CameraModel& camera,
                                   const TargetGeometry& target, double t, cv::Size image);

  // The fit state after the last estimate, for display and tests.
  int activePoints() const { return active_points_; }
  int activeDegree() const { return active_degree_; }
  double lastCorrelation() const { return last_r_; }
  // The extrapolated bounding box of the last estimate, before enlargement (thesis x~_{N+1}).
  const std::optional<cv::Rect2d>& lastPredictedBox() const { return last_box_; }
  std::size_t samples() const { return count_; }
  bool fromOneDetection() const { return count_ == 1; }

 private:
  struct Sample {
    double t = 0.0;
    std::array<double, 4> corners{};  // x0, y0, x1, y1
    std::array<double, 6> pose{};     // rx, ry, rz (unwrapped), tx, ty, tz
    bool has_pose = false;
  };
  const Sample& fromNewest(std::size_t k) const;  // k = 0 is the newest

  std::array<Sample, kHistory> ring_{};
  std::size_t head_ = 0;   // next write position
  std::size_t count_ = 0;
  // Fit state (3.3.1): grows back one step per observation after an r drop.
  int active_points_ = 0;
  int active_degree_ = 0;
  double last_r_ = 1.0;
  std::optional<cv::Rect2d> last_region_;
  std::optional<cv::Rect2d> last_box_;
};

}  // namespace imagepro
