#include "core/analysis/multi_target.h"

#include <algorithm>

#include "core/segmentation/threshold.h"

namespace imagepro {

int MultiTargetResult::reconstructed() const {
  return static_cast<int>(std::count_if(targets.begin(), targets.end(),
                                        [](const ReconstructedTarget& t) { return ok(t.status); }));
}

Status reconstructAllTargets(const Settings& settings, const cv::Mat& grey, MultiTargetWorkspace& ws,
                             MultiTargetResult& out) {
  const PipelineOptions& o = settings.pipeline;
  out.targets.clear();
  out.threshold = -1;
  auto fail = [&](Status s) {
    out.status = s;
    return s;
  };
  if (grey.empty() || grey.type() != CV_8UC1) return fail(Status::EmptyFrame);

  computeHistogram(grey, ws.histogram);
  Status s = computeThreshold(o.threshold, ws.histogram, out.threshold);
  if (!ok(s)) return fail(s);
  binarize(grey, out.threshold, ws.binary);
  s = detectEdges(o.edge_method, ws.binary, ws.edges, ws.edge_ws);
  if (!ok(s)) return fail(s);
  s = connectPaths(o.connectivity, ws.edges, grey.size(), ws.paths, ws.connectivity_ws);
  if (!ok(s)) return fail(s);

  EllipseOptions ellipse = o.ellipse;
  ellipse.report_all_targets = true;
  s = detectTarget(ellipse, settings.target, ws.paths, grey.size(), ws.ellipse_ws, ws.detections);
  if (!ok(s)) return fail(s);
  if (ws.detections.empty()) return fail(Status::NoTarget);

  const ReconstructionConfig config = reconstructionConfig(settings);
  for (const TargetDetection& d : ws.detections) {
    ReconstructedTarget t;
    t.ellipse = d.ellipse;
    t.bbox = d.bbox;
    t.status = reconstructTarget(config, grey, d.ellipse, out.threshold, ws.reconstruction_ws, ws.reconstruction);
    if (ok(t.status)) t.pose = ws.reconstruction.pose;
    out.targets.push_back(t);
  }
  std::sort(out.targets.begin(), out.targets.end(),
            [](const ReconstructedTarget& a, const ReconstructedTarget& b) { return a.ellipse.cx < b.ellipse.cx; });
  out.status = Status::Ok;
  return Status::Ok;
}

}  // namespace imagepro
