#pragma once
// Distance and angle measurement of thesis 5.3.1: an object carries two targets on
// two faces at a known angle, their centres a known distance apart (thesis fig. 5.2).
// Each target is reconstructed on its own (multi_target.h); the distance between the
// reconstructed centres and the angle between the reconstructed normals, compared
// with the known values, measure the on-site accuracy without another instrument.
//
// The virtual object: two plane faces meeting in an edge along the object's Y axis,
// the edge towards the camera (a convex corner, so neither card hides the other).
// In the object frame the two target centres lie at (-spacing / 2, 0, 0) and
// (+spacing / 2, 0, 0), the left target turned by +angle / 2 about Y and the right one
// by -angle / 2 (target +Z points into the object, docs/conventions.md), so their normals
// are `angle` apart and each faces the camera when the object does. The object's
// pose maps the object frame to the camera frame like a target's pose.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

#include "core/analysis/multi_target.h"
#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/options.h"

namespace imagepro {

// The object's known geometry.
struct TwoTargetObject {
  double spacing_mm = 200.0;  // distance between the two target centres
  double angle_deg = 90.0;    // angle between the two target normals (perpendicular faces)
};

struct TwoTargetMeasurement {
  double distance_mm = 0.0;  // between the reconstructed centres
  double angle_deg = 0.0;    // between the reconstructed normals
};

// Distance of the centres and angle of the normals (target +Z axes) of two poses.
TwoTargetMeasurement measureBetween(const Pose& a, const Pose& b);

// The measurement of one frame: Ok when exactly two targets were reconstructed.
// Fewer: the status of the first target whose reconstruction failed, or TooFewTargets
// when fewer than two were detected (or the frame's own status when it failed);
// more than two: AmbiguousTarget.
Status measureTwoTargets(const MultiTargetResult& frame, TwoTargetMeasurement& out);

// Poses (camera frame) of the left and right target of the object at `object_pose`.
std::array<Pose, 2> twoTargetPoses(const TwoTargetObject& object, const Pose& object_pose);

// True when each target's card (of side card_size_mm) fits on its face, i.e. between
// its centre and the edge; an angle in (0, 180) degrees.
bool twoTargetObjectFits(const TwoTargetObject& object, double card_size_mm);

// Three object positions in front of the camera for the study (the thesis measured
// from three camera positions): 1 square on, 2 and 3 turned and shifted. 1..3;
// anything else gives position 1.
Pose twoTargetStudyPosition(int position);

// The thesis's two lighting conditions (5.3.1): natural light (darker, uneven) and
// extra ceiling lights (brighter, even). Sets the scene's grey levels and gradient.
enum class StudyLighting : std::uint8_t { Natural, Extra };
void applyStudyLighting(StudyLighting lighting, VirtualSceneOptions& scene);

// Buffers of the two-target renderer, reused from frame to frame.
struct TwoTargetRenderWorkspace {
  cv::Mat left, right, cover, mask;  // CV_8UC1: each target alone, the right card's coverage
  cv::Mat grey, difference, alpha, noise;  // CV_32FC1 (alpha: 1 - coverage)
};

// Renders the object with both targets (virtual_renderer.h conventions and effects):
// each target is drawn on its card alone, then the right card is laid over the left
// render by its anti-aliased coverage, then the scene's gradient, blur and noise are
// applied once. Clutter (if any) lies behind both cards.
void renderTwoTargets(const CameraModel& camera, const TargetGeometry& target, const VirtualSceneOptions& scene,
                      const TwoTargetObject& object, const Pose& object_pose, cv::Mat& out,
                      std::uint64_t frame_seed, TwoTargetRenderWorkspace& ws);

}  // namespace imagepro
