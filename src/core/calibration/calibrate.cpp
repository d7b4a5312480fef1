#include "core/calibration/calibrate.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/calibration/pattern.h"
#include "core/calibration/spots.h"
#include "core/pipeline/engine.h"

namespace imagepro {
namespace {

// Everything kept for one image across the iterations.
struct ImageState {
  Status spotStatus = Status::Stopped;
  bool located = false;  // the target has given the pattern's pose once
  Pose pose;
  std::vector<ObservedSpot> observed;
  std::vector<IdealSpot> ideal;
  std::vector<SpotMatch> matches;
};

}  // namespace

PatternLocator targetPatternLocator(const Settings& settings) {
  Settings s = settings;
  // Each image on its own, through the whole pipeline, with distortion correction.
  s.pipeline.tracking.mode = TrackingMode::Off;
  s.pipeline.level = ApplicationLevel::Reconstruction;
  s.pipeline.reconstruction.distortion_correction = true;
  auto engine = std::make_shared<Engine>(s);
  return [engine, s](const cv::Mat& grey, const CameraModel& camera, Pose& pose) {
    Settings current = s;
    current.camera() = camera;
    engine->setSettings(current);
    engine->resetTracking();
    Frame frame;
    frame.image = grey;
    FrameResult result;
    engine->process(frame, result);
    if (!ok(result.status)) return result.status;
    if (!result.pose) return Status::NoTarget;
    pose = *result.pose;
    return Status::Ok;
  };
}

double coverageRadiusFraction(const CameraModel& camera, std::span<const CalibrationImageReport> images) {
  const Eigen::Vector2d pp(camera.u0(), camera.v0());
  double corner = 0.0;
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(0, 0), Eigen::Vector2d(camera.width, 0),
                                   Eigen::Vector2d(0, camera.height), Eigen::Vector2d(camera.width, camera.height)})
    corner = std::max(corner, (q - pp).norm());
  double reached = 0.0;
  for (const CalibrationImageReport& im : images)
    if (ok(im.status))
      for (const SpotCorrespondence& s : im.correspondences) reached = std::max(reached, (s.ideal_px - pp).norm());
  return corner > 0.0 ? reached / corner : 0.0;
}

Status iterateDistortion(const CameraModel& camera, const CalibrationOptions& options, const Distortion& start,
                         const DistortionMeasurement& measure, CalibrationResult& result,
                         const IterationCallback& onIteration, const PoseCorrectionCallback& onPoseCorrection) {
  result.status = Status::Stopped;
  result.distortion = start;
  result.converged = false;
  result.iterations = 0;
  result.rms_residual_px = 0.0;
  result.history.clear();

  std::vector<DistortionSample> samples;
  std::vector<PoseCorrection> corrections;
  Distortion estimate = start;
  for (int it = 1; it <= options.max_iterations; ++it) {
    samples.clear();
    corrections.clear();
    if (const Status s = measure(estimate, samples); !ok(s)) return result.status = s;
    bool withPoses = false;
    for (const DistortionSample& s : samples) withPoses = withPoses || s.image >= 0;
    withPoses = withPoses && options.refine_pose;
    Distortion next;
    const Status fit = withPoses ? fitDistortionAndPoses(samples, next, corrections) : fitDistortion(samples, next);
    if (!ok(fit)) return result.status = fit;

    CalibrationIteration record;
    record.iteration = it;
    record.distortion = next;
    record.relative_change = relativeParameterChange(camera, estimate, next);
    record.rms_residual_px = rmsResidualPx(next, samples, corrections);
    record.matches = static_cast<int>(samples.size());
    result.history.push_back(record);
    result.iterations = it;
    result.distortion = next;
    result.rms_residual_px = record.rms_residual_px;
    if (withPoses && onPoseCorrection) onPoseCorrection(corrections);
    if (onIteration) onIteration(record);

    if (!distortionPlausible(camera, next)) return result.status = Status::Diverged;
    estimate = next;
    if (record.relative_change < options.relative_change) {
      result.converged = true;
      return result.status = Status::Ok;
    }
  }
  return result.status = Status::Diverged;
}

Status calibrateDistortion(const Settings& settings, std::span<const cv::Mat> images, CalibrationResult& result,
                           const IterationCallback& onIteration, const PatternLocator& locator) {
  const CalibrationOptions& options = settings.pipeline.calibration;
  const PatternLocator locate = locator ? locator : targetPatternLocator(settings);

  std::vector<PatternSpot> pattern;
  patternSpots(settings.pattern, settings.target, pattern);

  // Step 5 once per image: the spots seen do not depend on the estimate.
  std::vector<ImageState> state(images.size());
  result.images.assign(images.size(), {});
  SpotFinderWorkspace finder;
  for (size_t i = 0; i < images.size(); ++i) {
    const bool cameraSize = images[i].cols == settings.camera().width && images[i].rows == settings.camera().height;
    state[i].spotStatus = images[i].empty() || cameraSize
                              ? findPatternSpots(images[i], settings.pipeline.threshold, finder, state[i].observed)
                              : Status::FrameSizeMismatch;
    result.images[i].status = state[i].spotStatus;
    result.images[i].spots_found = static_cast<int>(state[i].observed.size());
  }

  MatchWorkspace matchWs;
  // Steps 3, 4 and 6 over every image.
  const DistortionMeasurement measure = [&](const Distortion& estimate, std::vector<DistortionSample>& samples) {
    CameraModel camera = settings.camera();
    camera.distortion = estimate;
    const Eigen::Vector2d pp(camera.u0(), camera.v0());
    Status firstError = Status::Ok;
    int used = 0;
    for (size_t i = 0; i < images.size(); ++i) {
      ImageState& st = state[i];
      CalibrationImageReport& report = result.images[i];
      report.correspondences.clear();
      report.match = {};
      report.spots_expected = 0;
      Status s = st.spotStatus;
      if (ok(s) && (!st.located || !options.refine_pose)) {
        s = locate(images[i], camera, st.pose);
        if (ok(s) && !st.located) report.target_pose = st.pose;
        st.located = st.located || ok(s);
      }
      if (ok(s)) {
        report.pose = st.pose;
        projectPatternSpots(camera, settings.pattern, pattern, st.pose, st.ideal);
        report.spots_expected = static_cast<int>(st.ideal.size());
        matchSpots(camera, settings.pattern, st.ideal, st.observed, true, matchWs, st.matches, report.match);
        const int considered = report.match.matched + report.match.ambiguous;
        if (report.match.ambiguous > options.max_ambiguous_fraction * considered)
          s = Status::MatchAmbiguity;
        else if (report.match.matched < options.min_matches)
          s = Status::TooFewMatches;
      }
      report.status = s;
      if (!ok(s)) {
        if (ok(firstError)) firstError = s;
        continue;
      }
      ++used;
      const Eigen::Matrix3d R = rotationMatrix(st.pose);
      const Eigen::Vector3d T = translation(st.pose);
      for (const SpotMatch& m : st.matches) {
        const IdealSpot& ideal = st.ideal[m.ideal];
        const Eigen::Vector2d& mm = pattern[ideal.spot].position_mm;
        const Eigen::Vector2d& seen = st.observed[m.observed].centre;
        DistortionSample sample{ideal.ideal - pp, seen - ideal.ideal};
        if (options.refine_pose) {
          sample.image = static_cast<int>(i);
          sample.pose_jacobian = poseJacobian(camera, R * Eigen::Vector3d(mm.x(), mm.y(), 0.0) + T);
        }
        samples.push_back(sample);
        report.correspondences.push_back({mm, ideal.ideal, seen});
      }
    }
    return used > 0 ? Status::Ok : (ok(firstError) ? Status::TooFewMatches : firstError);
  };

  const PoseCorrectionCallback correct = [&](std::span<const PoseCorrection> corrections) {
    for (size_t i = 0; i < corrections.size() && i < state.size(); ++i) {
      if (!ok(result.images[i].status)) continue;
      state[i].pose = correctedPose(state[i].pose, corrections[i]);
      result.images[i].pose = state[i].pose;
    }
  };
  const IterationCallback record = [&](const CalibrationIteration& it) {
    CalibrationIteration copy = it;
    for (const CalibrationImageReport& r : result.images) copy.images_used += ok(r.status) ? 1 : 0;
    result.history.back().images_used = copy.images_used;
    if (onIteration) onIteration(copy);
  };
  const Status status = iterateDistortion(settings.camera(), options, Distortion{}, measure, result, record, correct);
  result.coverage_radius_fraction = coverageRadiusFraction(settings.camera(), result.images);
  if (ok(status) && result.coverage_radius_fraction < kMinCoverageRadiusFraction)
    return result.status = Status::PoorCoverage;
  return status;
}

}  // namespace imagepro
