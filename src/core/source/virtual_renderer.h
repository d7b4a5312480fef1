#pragma once
// Virtual perspective projection (thesis 2.2): draws the secondary passive target
// (white disk of radius R with a black spot of radius r0 at its centre and another
// at rf along +X, on a black square card) as the settings' camera sees it at a pose,
// with the camera's lens distortion applied. Binary mode gives the thesis's 0/255
// image; grey mode gives anti-aliased 8-bit grey with optional blur, noise,
// illumination gradient and clutter.
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

}  // namespace imagepro
