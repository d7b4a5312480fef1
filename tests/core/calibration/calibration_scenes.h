#pragma once
// Scenes shared by the calibration tests: the thesis's four calibration views of the
// pattern (+-45 deg about x and y, the target at the image centre), rendered by the
// Virtual source's renderer with a chosen lens distortion.
#include <opencv2/core.hpp>

#include <array>
#include <ostream>
#include <vector>

#include "core/calibration/spacing.h"
#include "core/common/status.h"
#include "core/settings/settings.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {

inline void PrintTo(Status s, std::ostream* os) { *os << statusName(s); }

namespace testing {

inline std::array<Pose, 4> calibrationViews() { return recommendedCalibrationViews(800.0); }

// Grey, blurred and noisy, as a camera would see the printed pattern.
inline VirtualSceneOptions realisticScene() {
  VirtualSceneOptions s;
  s.mode = RenderMode::Grey;
  s.blur_sigma_px = 0.8;
  s.noise_sigma = 3.0;
  return s;
}

inline std::vector<cv::Mat> renderViews(const Settings& settings, const Distortion& lens,
                                        const std::array<Pose, 4>& poses, const VirtualSceneOptions& scene) {
  CameraModel camera = settings.camera();
  camera.distortion = lens;
  std::vector<cv::Mat> images(poses.size());
  for (size_t i = 0; i < poses.size(); ++i)
    renderPattern(camera, settings.target, settings.pattern, scene, poses[i], images[i], i + 1);
  return images;
}

}  // namespace testing
}  // namespace imagepro
