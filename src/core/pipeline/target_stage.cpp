#include "core/pipeline/target_stage.h"

#include <chrono>

namespace imagepro {

namespace {
using Clock = std::chrono::steady_clock;
double microsecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}
}  // namespace

void TargetStage::run(const Settings& settings, const cv::Mat& grey, const Paths& paths, FrameResult& out) {
  const PipelineOptions& o = settings.pipeline;
  auto start = Clock::now();
  out.reached = ApplicationLevel::Ellipse;
  out.status = detectTarget(o.ellipse, settings.target, paths, grey.size(), ellipse_ws, detections);
  for (const TargetDetection& d : detections) {
    TargetSummary s;
    s.ellipse = d.ellipse;
    s.fit_error = d.fit_error;
    s.sampson_px = d.sampson_px;
    s.bennett_score = d.bennett_score;
    s.bennett_quality = d.bennett_quality;
    s.bennett_symmetry = d.bennett_symmetry;
    s.bbox = d.bbox;
    out.targets.push_back(s);
  }
  out.times[Stage::Ellipse] = microsecondsSince(start);
  if (!ok(out.status) || detections.empty()) {
    if (ok(out.status)) out.status = Status::NoTarget;
    return;
  }
  const TargetDetection& target = detections.front();
  out.detected_region = target.bbox;
  if (static_cast<int>(o.level) < static_cast<int>(ApplicationLevel::Reconstruction)) return;

  start = Clock::now();
  out.reached = ApplicationLevel::Reconstruction;
  out.status = reconstructTarget(settings, grey, target.ellipse, out.threshold, reconstruction_ws, reconstruction);
  for (const Eigen::Vector2d& p : reconstruction.contour)
    out.contour_points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  out.spots = {cv::Point2f(static_cast<float>(reconstruction.spots.centre_spot.x()),
                           static_cast<float>(reconstruction.spots.centre_spot.y())),
               cv::Point2f(static_cast<float>(reconstruction.spots.offset_spot.x()),
                           static_cast<float>(reconstruction.spots.offset_spot.y()))};
  if (ok(out.status)) out.pose = reconstruction.pose;
  out.times[Stage::Reconstruction] = microsecondsSince(start);
}

}  // namespace imagepro
