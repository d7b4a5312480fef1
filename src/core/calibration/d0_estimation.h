#pragma once
// The image plane distance d0 (thesis 4.1) from frames of the target: each frame's target
// is detected by the pipeline up to the ellipse, searched whole (d0 changes nothing before
// the reconstruction, and no tracking carries over between frames at different distances),
// then eq. 4.1 is iterated from d0 = f (core/reconstruction/image_plane_distance.h),
// reconstructing the target's depth with each d0 in turn. `imagepro-cli estimate-d0` and
// the application's d0 dialog both run this.
#include <span>
#include <vector>

#include "core/pipeline/engine.h"
#include "core/reconstruction/image_plane_distance.h"
#include "core/reconstruction/reconstruct.h"
#include "core/settings/settings.h"
#include "core/source/source.h"

namespace imagepro {

struct D0Options {
  double focal_length_mm = 0.0;  // the lens's f, d0(1) of eq. 4.1
  double epsilon_mm = 1e-6;      // eq. 4.2
  int max_iterations = 20;       // Diverged after this many steps
};

struct D0FrameEstimate {
  Status status = Status::Stopped;  // the detection's, NoTarget, or the iteration's
  ImagePlaneDistanceEstimate estimate;  // with its d0 after every step (history_mm)
};

class D0Estimator {
 public:
  // The settings' camera gives the pixel size, principal point and distortion; its d0 is
  // not used.
  D0Estimator(const Settings& settings, const D0Options& options);

  // The next frame of `source`: EndOfStream at its end (nothing else filled). `result` is
  // the frame's detection.
  Status step(FrameSource& source, FrameResult& result, D0FrameEstimate& out);
  // One given frame (CV_8UC1).
  void process(const Frame& frame, FrameResult& result, D0FrameEstimate& out);

 private:
  void estimate(const cv::Mat& image, const FrameResult& result, D0FrameEstimate& out);

  D0Options options_;
  Engine engine_;
  ReconstructionConfig config_;
  ReconstructionWorkspace ws_;
  ReconstructionResult reconstruction_;
};

// Mean and sample standard deviation of the estimates (0 for fewer than two).
struct D0Summary {
  int count = 0;
  double mean_mm = 0.0;
  double sd_mm = 0.0;
};
D0Summary summarizeD0(std::span<const double> d0_mm);

}  // namespace imagepro
