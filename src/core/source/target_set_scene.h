#pragma once
// Several printed targets in one frame with exact truth: each drawn on its own card at its
// own pose over what is drawn so far (composeTarget, real_scene.h), so a later card covers
// an earlier one as a card in front would. The test of a set of targets and its accuracy
// study draw their frames with it.
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/geometry.h"
#include "core/source/real_scene.h"

namespace imagepro {

// `targets[i]` drawn at `poses[i]` (the shorter list decides how many) over `background`
// (CV_8UC1, the camera's size) into `out` (CV_8UC1), before any imaging condition.
void composeTargets(const cv::Mat& background, const CameraModel& camera, const std::vector<TargetGeometry>& targets,
                    const TargetLook& look, const std::vector<Pose>& poses, cv::Mat& out);

}  // namespace imagepro
