#pragma once
// The detector's stage chain, written once (thesis figure 5.1 from the histogram to the
// pose): histogram of the searched region -> threshold -> edges -> connectivity ->
// ellipse detection -> crop target + re-threshold, features, distortion correction,
// analytic pose. The engine runs it inside its frame loop (with the tracker around it);
// the multi-target study and the CLI's detect, edges and threshold commands run it on
// stills and read the intermediate buffers it keeps. A detector stage is added here
// and nowhere else.
//
// Binarization (pipeline.binarization): the thesis's one threshold, a local threshold
// (local_threshold.h), or the first and, when its pass misses the target (no target, or
// a reconstruction that fails), the second: edges, paths, ellipses and the pose are then
// found once more on the local binary image, and that pass is kept when it finds the
// target, or, when both miss, when it got further through the stages.
//
// The chain stops after the settings' application level. Nothing here throws: every
// outcome is a Status in the FrameResult.
#include <opencv2/core.hpp>

#include <vector>

#include "core/connectivity/connectivity.h"
#include "core/connectivity/paths.h"
#include "core/edges/edge_list.h"
#include "core/edges/edges.h"
#include "core/ellipse/detect.h"
#include "core/pipeline/frame_result.h"
#include "core/reconstruction/reconstruct.h"
#include "core/segmentation/local_threshold.h"
#include "core/settings/settings.h"

namespace imagepro {

// Which targets of the frame are reconstructed: the best one (the frame loop), or every
// one the ellipse stage reports (report_all_targets implied; thesis 5.3.1's two targets).
enum class TargetsToReconstruct : std::uint8_t { Best, Every };

// Every stage's buffers and intermediate results, reused from frame to frame (no heap
// allocation once grown). Valid until the next run; all coordinates are full-image.
struct StageChain {
  // The pass whose result is reported (with global-then-local, maybe the second).
  cv::Mat binary;  // the searched region binarized (region-sized)
  EdgeList edges;
  Paths paths;
  std::vector<TargetDetection> detections;  // as the ellipse stage reported them
  // The other pass's buffers: the passes swap, so nothing is copied.
  struct Spare {
    cv::Mat binary;
    EdgeList edges;
    Paths paths;
    std::vector<TargetDetection> detections;
    std::vector<TargetSummary> targets;
  } spare;
  LocalThresholdWorkspace local_ws;
  EdgeWorkspace edge_ws;
  ConnectivityWorkspace connectivity_ws;
  EllipseWorkspace ellipse_ws;
  ReconstructionWorkspace reconstruction_ws;
  ReconstructionResult reconstruction;  // of the last target reconstructed
};

// Whether the chain ran `stage` (its status may still be a failure).
inline bool stageRan(const FrameResult& result, ApplicationLevel stage) {
  return static_cast<int>(result.reached) >= static_cast<int>(stage);
}

// Runs the chain on `region` of `grey` (clipped to the frame; the whole frame when
// empty) up to settings.pipeline.level. Fills in `out` everything the stages produce:
// status, reached, search_region, histogram, threshold, edge_pixels, paths, targets,
// detected_region, pose, contour_points, spots and the stage times from Crop to
// Reconstruction. The frame's identity (index, name, truth, timestamp) and the Grab
// and Tracking times are the caller's. With TargetsToReconstruct::Every each target
// carries its own reconstruction status and pose; out.status is then Ok when at least
// one target was detected, and out.pose is the first target's that reconstructed.
// `expected` (a tracked stream's last pose) decides between the rim's two circles where
// the spots cannot (otherwise AmbiguousPose, both poses in out.ambiguous_poses).
void runStageChain(const Settings& settings, const cv::Mat& grey, cv::Rect region, TargetsToReconstruct which,
                   StageChain& chain, FrameResult& out, const Pose* expected = nullptr);

}  // namespace imagepro
