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
// target, or, when both miss, when it got further through the stages. With the local
// window left to the image's size (window_px 0), last local passes with a narrow window
// (about a far target's disk: on a frame wider than 640 px one at the frame's scale, a
// 43rd of its width, then 15 px) follow a miss of every other, except on a whole frame
// searched right after a pose (a tracked stream's miss).
//
// Coarse search (pipeline.binarization.coarse_search): a whole frame at least
// 2 * kCoarseWidthPx wide (reduce.h), searched for the best target down to its pose, is
// first searched reduced: each binarization's pass runs on the frame reduced k times
// (k = coarseFactor(width): 2 at 640 x 480) before any runs on the frame itself. A tracked
// region is searched at its own size. A reduced pass finds the ellipse; the pose is then
// reconstructed from the frame itself (the crop, its re-threshold, the sub-pixel rim and
// the spots), so a found pose is as exact as the full pass's. A miss at the reduced size
// (a far target's rim too small, its spots merged) falls through to the full-size passes.
// When a reduced pass is the one reported, its edges and paths are given at the pixels
// nearest the centres of their k x k blocks, and its binary image stays reduced in
// chain.binary: regionBinary enlarges it for a display.
//
// The chain stops after the settings' application level. Nothing here throws: every
// outcome is a Status in the FrameResult.
#include <opencv2/core.hpp>

#include <cstdint>
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
  cv::Mat binary;  // the searched region binarized (region-sized; reduced by reported_factor: regionBinary)
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
    int factor = 1;
  } spare;
  int reported_factor = 1;  // the reported pass's reduction (1: the region itself)
  cv::Rect region;          // the searched region, clipped to the frame
  cv::Mat reduced;          // the searched region reduced (coarse search)
  cv::Mat enlarged_binary;  // where a reported reduced pass's binary image is enlarged
  std::vector<std::uint16_t> reduce_ws;
  LocalThresholdWorkspace local_ws;
  EdgeWorkspace edge_ws;
  ConnectivityWorkspace connectivity_ws;
  // The reduced passes' own: its index image has the reduced image's size, and sharing
  // one would rebuild it at every change of size.
  ConnectivityWorkspace reduced_connectivity_ws;
  EllipseWorkspace ellipse_ws;
  ReconstructionWorkspace reconstruction_ws;
  ReconstructionResult reconstruction;  // of the last target reconstructed
  std::vector<TargetSummary> told;      // a set's targets told by the passes so far (told_targets.h)
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
// the spots cannot (otherwise AmbiguousPose, both poses in out.ambiguous_poses). A region's
// histogram (not the whole frame's) is taken on every k-th row, at least 8192 pixels, its
// counts scaled back by k. With TargetsToReconstruct::Best, several targets found are
// first each reconstructed: exactly one with a pose that fits is the target.
void runStageChain(const Settings& settings, const cv::Mat& grey, cv::Rect region, TargetsToReconstruct which,
                   StageChain& chain, FrameResult& out, const Pose* expected = nullptr);

// With TargetsToReconstruct::Every and a set of targets in the settings, the passes go on
// until every member is told, each pass's told targets gathered (told_targets.h): out.targets
// is then every target told, in the set's order, out.set_of_targets is true, and the frame's
// own pose, id, box and self-check are the shown target's (adoptShownTarget).

// Makes the frame's own fields those of its shown target (settings frames.shown_target, or
// the first member told, told_targets.h) among out.targets; out.status is Ok when any
// target has a pose. The rim's contour points are cleared (each target keeps its spots).
void adoptShownTarget(const Settings& settings, FrameResult& out);

// Whether a run (or one pass of it) missed the target: a failure after the threshold was
// found, or, with every target reconstructed, none that reconstructed. Two targets
// (AmbiguousTarget) or two poses (AmbiguousPose) are findings of the target, not misses.
bool missedTarget(const FrameResult& out, TargetsToReconstruct which);

// The last run's binary image at the searched region's size: chain.binary, or, when a
// reduced pass was reported, that image enlarged block by block into
// chain.enlarged_binary (white where the region's last rows and columns made no whole
// block). Done on demand: only a display needs it, and it costs as much as a small frame.
const cv::Mat& regionBinary(StageChain& chain);

}  // namespace imagepro
