#pragma once
// Real-scene frames with exact ground truth: the target of the settings,
// on its black card, drawn at a known pose over a photograph, then the whole frame
// put through the imaging conditions of scene_conditions.h.
//
// The target is drawn by the Virtual source's renderer (virtual_renderer.h: the same
// projection and lens model, anti-aliased), so the truth is the pose it was drawn at.
// The renderer paints a flat background, so it draws twice, over black and over white:
// where a pixel is covered by the card or disk a fraction c, the two differ by
// (1 - c) * 255, and the photograph shows through by exactly that fraction.
//
// Stills: a photograph cut to the camera's size, the target 0.4-2.5 m away, tilted
// 0-60 deg from its line of sight, turned at random about its normal, its card wholly
// inside the frame, paper white 170-235 and card black 10-40, with the still
// conditions of randomStillConditions(). Everything is drawn from (seed, index), so a
// set is reproducible. A negative is the same draw without the target. A webcam set
// adds rig effects (rig_effects.h) from a stream of their own.
#include <opencv2/core.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/common/geometry.h"
#include "core/settings/settings.h"
#include "core/source/background_photos.h"
#include "core/source/rig_effects.h"
#include "core/source/scene_conditions.h"

namespace imagepro {

// How the printed target looks: grey levels of the paper and the card, card side.
struct TargetLook {
  int white = 230;
  int black = 20;
  double card_size_mm = 130.0;  // at least the disk's diameter is drawn
};

struct RealSceneFrame {
  cv::Mat image;              // CV_8UC1, the camera's size
  std::optional<Pose> truth;  // the pose the target was drawn at; none without a target
  std::string background;     // the photograph's path
  SceneConditions conditions;
  TargetLook look;
  RigDraw rig;  // the occluder, glare and dim light drawn (none outside a webcam set)
};

// The pose that puts the disk centre `distance_mm` along the ray through the ideal
// pixel `centre`, its normal tilted `tilt_deg` from that line of sight about an axis
// at `tilt_azimuth_deg` (in the plane across the line of sight), and turned
// `inplane_deg` about its own normal; it faces the camera for tilts below 90 deg.
Pose poseAlongRay(const CameraModel& camera, const Eigen::Vector2d& centre, double distance_mm, double tilt_deg,
                  double tilt_azimuth_deg, double inplane_deg);

// True when the target faces the camera and its card (side look.card_size_mm, at
// least the disk) lies in front of the camera and inside the image, `margin_px` clear
// of the border (lens distortion applied).
bool cardInFrame(const CameraModel& camera, const TargetGeometry& target, double card_size_mm, const Pose& pose,
                 double margin_px);

// Puts an opaque object over `background` (CV_8UC1): `paint(level, out)` draws it, anti-aliased,
// over a flat CV_8UC1 frame of grey `level` of the background's size, and is called for 0
// and 255. `scene` is CV_32FC1 grey levels, the photograph showing through wherever the
// object covers a pixel only partly.
void composeOver(const cv::Mat& background, const std::function<void(int level, cv::Mat& out)>& paint,
                 cv::Mat& scene);

// Draws the target at `pose` over `background` (CV_8UC1, the camera's size): `scene` is
// CV_32FC1 grey levels, before any imaging condition.
void composeTarget(const cv::Mat& background, const CameraModel& camera, const TargetGeometry& target,
                   const TargetLook& look, const Pose& pose, cv::Mat& scene);

// What a frame shows at its pose, over the photograph cut to the frame (`background`, CV_8UC1),
// into `scene` (CV_32FC1, before the imaging conditions). Empty: the target (composeTarget).
// Another object, such as a reference marker, drawn through the same draws of pose, look,
// photograph and conditions gives that object's twin of the frame.
using ScenePainter = std::function<void(const cv::Mat& background, const Pose& pose, const TargetLook& look,
                                        cv::Mat& scene)>;

// Still frames and negatives over the photographs `photos`.
class RealScenes {
 public:
  // `rig` adds occluders, glare and dim light to a share of the stills (rig_effects.h); the
  // draws of everything else stay as they are without it, so a seed shows the same scenes.
  RealScenes(const Settings& settings, std::vector<std::string> photos, RigEffects rig = {});

  // Still `index` of the set `seed`; `with_target` false gives its negative. False with
  // `error` when there is no photograph or the one drawn cannot be read. `painter` draws
  // something else than the target at the still's pose (truth stays that pose).
  bool still(std::uint64_t seed, std::int64_t index, bool with_target, RealSceneFrame& out, std::string& error,
             const ScenePainter& painter = {}) const;

  // The target drawn over `background` by `painter`, or composeTarget when it is empty.
  void paint(const ScenePainter& painter, const cv::Mat& background, const Pose& pose, const TargetLook& look,
             cv::Mat& scene) const;

  // Still `index`'s pose alone (what still() draws the target at).
  Pose stillPose(std::uint64_t seed, std::int64_t index) const;

  const std::vector<std::string>& photos() const { return photos_; }
  const Settings& settings() const { return settings_; }
  const RigEffects& rigEffects() const { return rig_; }
  // The photograph `path` cut to the camera's size as (zoom, fx, fy) say.
  bool background(const std::string& path, double zoom, double fx, double fy, cv::Mat& out,
                  std::string& error) const;

  static constexpr double kMinDistanceMm = 400.0;
  static constexpr double kMaxDistanceMm = 2500.0;
  static constexpr double kMaxTiltDeg = 60.0;

 private:
  Settings settings_;
  std::vector<std::string> photos_;
  RigEffects rig_;
  PhotoCache cache_;
};

}  // namespace imagepro
