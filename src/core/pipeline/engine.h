#pragma once
// The frame loop's one object (thesis figure 5.1): grab -> crop to the tracked region
// (+ histogram) -> threshold -> edges -> connectivity -> ellipse detection -> crop
// target + re-threshold -> features -> distortion correction -> 3D reconstruction
// -> tracker. Used unchanged by the GUI's worker thread and by the CLI. With a set of
// targets in the settings (target_set.h) every member is followed, one tracker each
// (engine_set.cpp), and the frame result lists every target told.
// Settings replaced with setSettings() take effect at the next frame; the
// application level stops a frame after any stage. Nothing here throws: every
// outcome is a Status in the FrameResult, and the next frame is processed as usual.
#include <memory>

#include "core/connectivity/paths.h"
#include "core/edges/edge_list.h"
#include "core/pipeline/frame_result.h"
#include "core/settings/settings.h"
#include "core/source/source.h"

namespace imagepro {

class Engine {
 public:
  Engine();
  explicit Engine(const Settings& settings);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  // Takes effect from the next frame. Tracking history is kept.
  void setSettings(const Settings& settings);
  const Settings& settings() const;

  // Runs the pipeline and the tracker on one frame.
  void process(const Frame& frame, FrameResult& out);
  // Grabs the next frame from `source` and processes it. A grab error is reported in
  // `out.status` (and returned); the caller decides whether to go on (EndOfStream ends a file list).
  Status step(FrameSource& source, FrameResult& out);
  // Forgets the tracking history: the next frame searches the whole image.
  void resetTracking();

  // The last frame's intermediate data, for display; valid until the next process().
  const Frame& lastFrame() const;
  const cv::Mat& binaryImage() const;  // the searched region, thresholded (region-sized)
  const EdgeList& edges() const;       // full-image coordinates
  const Paths& paths() const;          // full-image coordinates

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace imagepro
