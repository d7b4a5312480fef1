#include "core/source/target_set_scene.h"

#include <algorithm>

namespace imagepro {

void composeTargets(const cv::Mat& background, const CameraModel& camera, const std::vector<TargetGeometry>& targets,
                    const TargetLook& look, const std::vector<Pose>& poses, cv::Mat& out) {
  background.copyTo(out);
  cv::Mat scene;
  for (std::size_t i = 0; i < std::min(targets.size(), poses.size()); ++i) {
    composeTarget(out, camera, targets[i], look, poses[i], scene);
    scene.convertTo(out, CV_8U);
  }
}

}  // namespace imagepro
