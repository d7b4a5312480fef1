#include "core/calibration/calibration_check.h"

namespace imagepro {

Status checkCalibrationView(const Settings& settings, const cv::Mat& grey, const Pose& pose,
                            CalibrationCheckWorkspace& ws, CalibrationCheck& out) {
  out.ideal.clear();
  out.seen.clear();
  out.matches.clear();
  out.stats = {};
  if (grey.empty() || grey.type() != CV_8UC1) return out.status = Status::EmptyFrame;
  const CameraModel& camera = settings.camera();
  if (grey.cols != camera.width || grey.rows != camera.height) return out.status = Status::FrameSizeMismatch;
  patternSpots(settings.pattern, settings.target, ws.pattern);  // a few thousand spots: cheap beside step 5
  projectPatternSpots(camera, settings.pattern, ws.pattern, pose, ws.ideal);  // step 4
  for (const IdealSpot& s : ws.ideal) out.ideal.push_back(s.ideal);
  const Status found = findPatternSpots(grey, settings.pipeline.threshold, ws.finder, ws.observed);  // step 5
  if (!ok(found)) return out.status = found;
  for (const ObservedSpot& s : ws.observed) out.seen.push_back(s.centre);
  matchSpots(camera, settings.pattern, ws.ideal, ws.observed, true, ws.match, ws.matches, out.stats);  // step 6
  for (const SpotMatch& m : ws.matches) out.matches.emplace_back(m.ideal, m.observed);
  return out.status = Status::Ok;
}

}  // namespace imagepro
