#pragma once
// Virtual perspective projection (thesis 2.2): draws the secondary passive target
// (white disk of radius R with a black spot of radius r0 at its centre and another
// at rf along +X, on a black square card) as the settings' camera sees it at a pose,
// with the camera's lens distortion applied. Binary mode gives the thesis's 0/255
// image; grey mode gives anti-aliased 8-bit grey with optional blur, noise,
// illumination gradient and clutter.
//
// Rendering is by inverse mapping, so the ground truth is exact: every image sample
// (distorted pixel coordinates) is undistorted by inverting eq. 4.7 with Newton's
// method, back-projected, and its ray intersected with the target plane (the pose
// of docs/conventions.md), where the point is classified. Binary mode samples pixel
// centres. Grey mode averages supersampling^2 samples over the area of each pixel
// that lies on an edge, then applies, in this order: illumination gradient (brightness
// scaled by 1 + g * (u / (width - 1) - 0.5)), Gaussian blur, Gaussian noise.
// Clutter (white bars and rectangles fixed in the image, placed from scene.seed) lies
// behind the card, so it never overlaps it; it is drawn in both modes. In grey mode
// the Room backdrop (the settings' default for the Virtual source; scene_shapes.h) puts
// a lit room behind the card instead of one flat grey: a wall with a window and a picture, a desk with books, a
// monitor, a keyboard, a mug and a cable, lit brighter on the window's side and
// darker towards the corners (the light multiplies the target too, as a room's would).
// Plain keeps the thesis's flat background_level.
// A target behind the camera or seen edge-on is simply not in the image; seen from
// behind, the card (and the pattern's sheet) shows its plain black back. Image points
// beyond the fold of an extreme distortion model (no undistorted position) see the
// background. Per-camera tables and work images are kept per thread between calls, so
// steady-state rendering allocates nothing itself (OpenCV's blur may, internally).
#include <opencv2/core.hpp>

#include <cstdint>

#include "core/common/geometry.h"
#include "core/settings/options.h"

namespace imagepro {

// Renders into `out` (resized to camera.width x camera.height, CV_8UC1).
// `frame_seed` varies the noise from frame to frame (clutter stays put for a scene).
void renderTarget(const CameraModel& camera, const TargetGeometry& target,
                  const VirtualSceneOptions& scene, const Pose& pose, cv::Mat& out,
                  std::uint64_t frame_seed = 0);

// Renders the calibration pattern (thesis 4.3, docs/conventions.md): a white sheet of
// columns x rows spacings, carrying the target on its black card of side
// pattern.card_size_mm at the centre and a grid of black spots centred on the target,
// without the grid spots that would touch the card. `pose` is the target's pose.
// Colours and effects as renderTarget (the sheet is white_level, beyond it the
// background, whatever scene.backdrop says); scene.card_size_mm is not used.
void renderPattern(const CameraModel& camera, const TargetGeometry& target,
                   const PatternGeometry& pattern, const VirtualSceneOptions& scene,
                   const Pose& pose, cv::Mat& out, std::uint64_t frame_seed = 0);

// True when the target faces the camera and its whole disk (edge sampled at 1 degree,
// distortion applied) lies in front of the camera and inside the image.
bool targetInView(const CameraModel& camera, const TargetGeometry& target, const Pose& pose);

}  // namespace imagepro
