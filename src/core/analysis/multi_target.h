#pragma once
// Every target of one frame, each with its own pose: the measurement of thesis 5.3.1
// reconstructs the two targets of its object "separately". The frame goes through the
// pipeline's stage chain (stage_chain.h) with every target reconstructed: threshold of
// the whole frame, edges, connectivity, the ellipse stage reporting every target it
// finds, and each target reconstructed by the chain of thesis 5.2.2 on its own crop,
// with its own re-threshold. No tracking: the whole frame is searched every time.
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"
#include "core/ellipse/ellipse.h"
#include "core/pipeline/frame_result.h"
#include "core/pipeline/stage_chain.h"
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
  StageChain chain;
  FrameResult frame;
};

// Reconstructs every target of `grey` with the settings' methods (report_all_targets is
// implied). The first failing frame stage (EmptyFrame, ThresholdUndefined, NoEdges,
// NoTarget ...) is the result's status and leaves `targets` empty; a target whose
// reconstruction fails keeps its own status and the others go on.
Status reconstructAllTargets(const Settings& settings, const cv::Mat& grey, MultiTargetWorkspace& ws,
                             MultiTargetResult& out);

}  // namespace imagepro
