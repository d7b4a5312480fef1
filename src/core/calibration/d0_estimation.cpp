#include "core/calibration/d0_estimation.h"

#include <algorithm>
#include <cmath>

namespace imagepro {

namespace {
Settings detectionSettings(Settings s) {
  s.pipeline.level = ApplicationLevel::Ellipse;
  s.pipeline.tracking.mode = TrackingMode::Off;
  return s;
}
}  // namespace

D0Estimator::D0Estimator(const Settings& settings, const D0Options& options)
    : options_(options), engine_(detectionSettings(settings)), config_(reconstructionConfig(settings)) {}

Status D0Estimator::step(FrameSource& source, FrameResult& result, D0FrameEstimate& out) {
  if (engine_.step(source, result) == Status::EndOfStream) return Status::EndOfStream;
  estimate(engine_.lastFrame().image, result, out);
  return out.status;
}

void D0Estimator::process(const Frame& frame, FrameResult& result, D0FrameEstimate& out) {
  engine_.process(frame, result);
  estimate(frame.image, result, out);
}

void D0Estimator::estimate(const cv::Mat& image, const FrameResult& result, D0FrameEstimate& out) {
  out.estimate = {};
  out.status = result.status;
  if (ok(out.status) && result.targets.empty()) out.status = Status::NoTarget;
  if (!ok(out.status)) return;
  const Ellipse rim = result.targets.front().ellipse;
  const auto depthAt = [&](double d0, double& depth) {
    config_.camera.image_plane_distance_mm = d0;
    const Status s = reconstructTarget(config_, image, rim, result.threshold, ws_, reconstruction_);
    depth = reconstruction_.pose.tz_mm;
    return s;
  };
  out.status = estimateImagePlaneDistance(options_.focal_length_mm, depthAt, options_.epsilon_mm,
                                          options_.max_iterations, out.estimate);
}

D0Summary summarizeD0(std::span<const double> d0_mm) {
  D0Summary s;
  s.count = static_cast<int>(d0_mm.size());
  if (s.count == 0) return s;
  double sum = 0.0;
  for (double d : d0_mm) sum += d;
  s.mean_mm = sum / s.count;
  if (s.count < 2) return s;
  double squares = 0.0;
  for (double d : d0_mm) squares += (d - s.mean_mm) * (d - s.mean_mm);
  s.sd_mm = std::sqrt(squares / (s.count - 1));
  return s;
}

}  // namespace imagepro
