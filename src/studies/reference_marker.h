#pragma once
// The reference of the accuracy study (docs/accuracy.md): an ArUco marker (OpenCV aruco,
// DICT_4X4_50) whose black square is as wide as the target's disk, on a white card,
// seen at the target's very pose through the same camera, lens distortion, blur and noise.
// It is found by OpenCV's detector with sub-pixel corner refinement, its corners are
// corrected for the lens distortion like the target's features, and its pose comes from
// cv::solvePnP with SOLVEPNP_IPPE_SQUARE. The marker frame shares the target frame's
// conventions: +X to the right of the printed marker, +Y down it, +Z away from the camera.
#include <opencv2/core.hpp>

#include <cstdint>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/settings/options.h"

namespace imagepro::studies {

struct MarkerGeometry {
  double square_mm = 100.0;  // side of the black square (border included)
  double card_mm = 130.0;    // side of the white card around it
  int id = 0;                // in DICT_4X4_50
};

// Replaces the pixels of `frame` (CV_8UC1, the camera's size: the scene without blur,
// noise or gradient) that see the marker's card at `pose` by the card: white_level and
// black_level of `scene`, anti-aliased with scene.supersampling^2 samples on edge pixels.
void paintMarkerCard(const CameraModel& cam, const MarkerGeometry& marker, const VirtualSceneOptions& scene,
                     const Pose& pose, cv::Mat& frame);

// The virtual renderer's image effects, in its order: illumination gradient, Gaussian blur,
// Gaussian noise (grey levels), rounding to 8 bits. `seed` draws the noise.
void applySceneEffects(const VirtualSceneOptions& scene, std::uint64_t seed, cv::Mat& frame);

// NoTarget when the marker is not found, AmbiguousTarget when found twice; the solver's
// failure is Diverged.
Status estimateMarkerPose(const CameraModel& cam, const MarkerGeometry& marker, const cv::Mat& grey, Pose& out);

}  // namespace imagepro::studies
