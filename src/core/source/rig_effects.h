#pragma once
// What a real rig does to the printed target, for the real-scene stills: a flat
// occluder lying across the rim (tape, a clamp, a finger, a cable), a saturating glare on
// the paper, and a dim room. Occluder and glare lie in the target's plane and are drawn
// through the camera's projection and lens, after the target (or a reference marker drawn
// at the same pose) and before the imaging conditions, so light, blur, noise and JPEG act
// on them as on the target. Everything is drawn from the still's own random stream.
//
//  * Occluder: a strip 10-25 mm wide, dark (grey 15-60) or grey (70-160), clear of both
//    spots by 1 mm. Half are tape across the disk (a chord strip running past the card on
//    both sides), half a clamp or finger reaching in from beyond the card to a tip inside
//    the disk, within 60 deg of the radial direction.
//  * Glare: a disk 4-12 mm across on the paper, clear of the spots by 1 mm, whose light adds
//    1.2-2.5 times full scale in its core (saturating) and fades over a fifth of its size.
//  * Dim: paper at grey 70-120, the card at 5-20.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "core/common/geometry.h"
#include "core/source/scene_conditions.h"

namespace imagepro {

// The share of stills that get each effect (0: none, the plain real-scene stills).
struct RigEffects {
  double occluder_fraction = 0.0;
  double glare_fraction = 0.0;
  double dim_fraction = 0.0;
  bool any() const { return occluder_fraction > 0.0 || glare_fraction > 0.0 || dim_fraction > 0.0; }
};

// The webcam set (docs/accuracy.md): occluders on half the stills, glare and dim light on 30 %.
inline constexpr RigEffects kWebcamRigEffects{0.5, 0.3, 0.3};

// A strip in the target plane (mm) from `from` to `to`, `width_mm` wide, of grey `level`.
struct Occluder {
  bool present = false;
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  double width_mm = 0.0;
  int level = 0;
};

// A glare disk in the target plane (mm): centre, diameter, added light in its core (grey levels).
struct Glare {
  bool present = false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double diameter_mm = 0.0;
  double strength = 0.0;
};

struct RigDraw {
  Occluder occluder;
  Glare glare;
  bool dim = false;
  int dim_white = 0, dim_black = 0;  // the look's levels when dim
};

// Draws a still's effects from `random` (each one's share as `effects` says), the target
// geometry deciding where the spots are to be kept clear.
RigDraw drawRigEffects(const RigEffects& effects, const TargetGeometry& target, double card_size_mm,
                       SceneRandom& random);

// Paints the occluder and the glare of `draw` over `scene` (CV_32FC1 grey levels, the
// camera's size), the target at `pose`. Parts behind the camera are not drawn.
void paintRigEffects(const RigDraw& draw, const CameraModel& camera, const Pose& pose, cv::Mat& scene);

// The distance (mm) from `p` to the segment from `a` to `b`.
double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

}  // namespace imagepro
