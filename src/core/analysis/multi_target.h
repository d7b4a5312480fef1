#pragma once
// Every target of one frame, each with its own pose: the measurement of thesis 5.3.1
// reconstructs the two targets of its object "separately". The frame goes through the
// pipeline's stages (threshold of the whole frame, edges, connectivity), the ellipse
// stage reports every target it finds (EllipseOptions::report_all_targets), and each
// is reconstructed by the reconstruction chain of thesis 5.2.2 on its own crop, with
// its own re-threshold. No tracking: the whole frame is searched every time.
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/connectivity/connectivity.h"
#include "core/connectivity/paths.h"
#include "core/edges/edge_list.h"
#include "core/edges/edges.h"
#include "core/ellipse/detect.h"
#include "core/reconstruction/reconstruct.h"
#include "core/segmentation/histogram.h"
#include "core/settings/settings.h"

namespace imagepro {

// One target of the frame: where it was found and what its reconstruction gave.
struct ReconstructedTarget {
  Ellipse ellipse;              // as detected (image px as seen)
  cv::Rect bbox;                // of its rim's path
  Status status = Status::Stopped;  // of its reconstruction
  Pose pose;                    // valid when status is Ok
};

struct MultiTargetResult {
  Status status = Status::Stopped;  // of the frame stages; Ok when at least one target was detected
  int threshold = -1;
  std::vector<ReconstructedTarget> targets;  // left to right (by ellipse centre u)
  // Reconstructed poses in `targets`.
  int reconstructed() const;
};

// Buffers reused from frame to frame: no heap allocation once they have grown.
struct MultiTargetWorkspace {
  Histogram histogram{};
  cv::Mat binary;
  EdgeList edges;
  EdgeWorkspace edge_ws;
  Paths paths;
  ConnectivityWorkspace connectivity_ws;
  EllipseWorkspace ellipse_ws;
  std::vector<TargetDetection> detections;
  ReconstructionWorkspace reconstruction_ws;
  ReconstructionResult reconstruction;
};

// Reconstructs every target of `grey` with the settings' methods (report_all_targets is
// implied). The first failing frame stage (EmptyFrame, ThresholdUndefined, NoEdges,
// NoTarget ...) is the result's status and leaves `targets` empty; a target whose
// reconstruction fails keeps its own status and the others go on.
Status reconstructAllTargets(const Settings& settings, const cv::Mat& grey, MultiTargetWorkspace& ws,
                             MultiTargetResult& out);

}  // namespace imagepro
