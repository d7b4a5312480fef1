#include "core/analysis/multi_target.h"

#include <algorithm>


namespace imagepro {

int MultiTargetResult::reconstructed() const {
  return static_cast<int>(std::count_if(targets.begin(), targets.end(),
                                        [](const ReconstructedTarget& t) { return ok(t.status); }));
}

Status reconstructAllTargets(const Settings& settings, const cv::Mat& grey, MultiTargetWorkspace& ws,
                             MultiTargetResult& out) {
  out.targets.clear();
  // Every stage runs, whatever application level the settings stop at.
  if (settings.pipeline.level != ApplicationLevel::Reconstruction) {
    Settings all = settings;
    all.pipeline.level = ApplicationLevel::Reconstruction;
    return reconstructAllTargets(all, grey, ws, out);
  }
  FrameResult& frame = ws.frame;
  runStageChain(settings, grey, {}, TargetsToReconstruct::Every, ws.chain, frame);
  out.status = frame.status;
  out.threshold = frame.threshold;
  if (!ok(frame.status)) return frame.status;
  for (const TargetSummary& target : frame.targets) {
    ReconstructedTarget t;
    t.ellipse = target.ellipse;
    t.bbox = target.bbox;
    t.status = target.status;
    if (target.pose) t.pose = *target.pose;
    out.targets.push_back(t);
  }
  std::sort(out.targets.begin(), out.targets.end(),
            [](const ReconstructedTarget& a, const ReconstructedTarget& b) { return a.ellipse.cx < b.ellipse.cx; });
  return Status::Ok;
}

}  // namespace imagepro
