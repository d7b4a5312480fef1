#pragma once
// The engine's target stage: ellipse detection and target selection (thesis 2.6),
// then the reconstruction chain (crop + re-threshold, features, distortion
// correction, fit, analytic pose; thesis 5.2.2) for the target found. Kept apart
// from the frame loop so each half stays readable.
#include <opencv2/core.hpp>

#include <vector>

#include "core/connectivity/paths.h"
#include "core/ellipse/detect.h"
#include "core/pipeline/frame_result.h"
#include "core/reconstruction/reconstruct.h"
#include "core/settings/settings.h"

namespace imagepro {

struct TargetStage {
  EllipseWorkspace ellipse_ws;
  std::vector<TargetDetection> detections;
  ReconstructionWorkspace reconstruction_ws;
  ReconstructionResult reconstruction;

  // Fills out.targets, out.detected_region, out.pose, the display features and the
  // Ellipse and Reconstruction stage times; sets out.status and out.reached.
  void run(const Settings& settings, const cv::Mat& grey, const Paths& paths, FrameResult& out);
};

}  // namespace imagepro
