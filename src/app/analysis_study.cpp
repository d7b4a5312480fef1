#include "app/analysis_study.h"

#include <algorithm>

#include "core/analysis/pendulum_scene.h"
#include "core/analysis/pose_series.h"
#include "core/pipeline/engine.h"
#include "core/source/virtual_motion.h"

namespace imagepro::app {

namespace {

std::string inWords(Status s) { return std::string(statusName(s)) + ": " + std::string(statusMessage(s)); }

}  // namespace

// ---- Pendulum -------------------------------------------------------------------

void analysePendulumSamples(PendulumStudyResult& result) {
  PendulumAnalysisOptions options;
  options.amplitude_correction = result.amplitude_correction;
  result.analysis = PendulumAnalysis{};
  result.status = analyzePendulum(result.samples, options, result.analysis);
  result.error.clear();
  if (!ok(result.status))
    result.error = inWords(result.status) + " (" + std::to_string(result.analysis.valid_frames) + " of " +
                   std::to_string(result.samples.size()) + " frames with a pose)";
}

PendulumStudyResult runPendulumFile(const std::string& path, double rate_hz, bool amplitude_correction) {
  PendulumStudyResult result;
  result.amplitude_correction = amplitude_correction;
  result.status = readPoseSeries(path, rate_hz, result.samples, result.error);
  if (!ok(result.status)) {
    result.error = std::string(statusName(result.status)) + ": " + result.error;
    return result;
  }
  analysePendulumSamples(result);
  return result;
}

PendulumStudyResult runVirtualPendulum(const Settings& settings, const VirtualPendulumParams& params,
                                       StudyProgress& progress) {
  PendulumStudyResult result;
  result.amplitude_correction = params.amplitude_correction;
  Settings s = settings;
  s.virtual_scene.noise_sigma = params.noise_sigma;
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  result.has_truth = true;
  result.truth = {truth.length_mm, pendulumPeriodS(truth), truth.gravity_m_s2};

  progress.total.store(params.frames);
  PendulumSource source(s, MotionBlur{});
  Engine engine(s);
  FrameResult r;
  result.samples.reserve(static_cast<std::size_t>(std::max(0, params.frames)));
  for (int i = 0; i < params.frames; ++i) {
    if (progress.cancel.load()) {
      result.status = Status::Stopped;
      result.error = "cancelled";
      return result;
    }
    engine.step(source, r);
    imagepro::PoseSample sample;
    sample.t_s = r.timestamp_s;
    sample.valid = ok(r.status) && r.pose.has_value();
    if (sample.valid) sample.pose = *r.pose;
    result.samples.push_back(sample);
    progress.done.store(i + 1);
  }
  analysePendulumSamples(result);
  return result;
}

void retimeSamples(std::vector<imagepro::PoseSample>& samples, const std::vector<std::int64_t>& indices,
                   double rate_hz) {
  bool increasing = true;
  for (std::size_t i = 1; increasing && i < samples.size(); ++i) increasing = samples[i].t_s > samples[i - 1].t_s;
  if (increasing || !(rate_hz > 0.0)) return;
  for (std::size_t i = 0; i < samples.size() && i < indices.size(); ++i)
    samples[i].t_s = static_cast<double>(indices[i]) / rate_hz;
}

// ---- Two targets ----------------------------------------------------------------

TwoTargetMeasurer::TwoTargetMeasurer(const Settings& settings) {
  for (int c = 0; c < kCorrections; ++c) {
    runs[c] = settings;
    runs[c].pipeline.reconstruction.distortion_correction = kCorrectionOn[c];
  }
}

void TwoTargetMeasurer::measure(const cv::Mat& grey, TwoTargetFrame& frame) {
  for (int c = 0; c < kCorrections; ++c) {
    frame.status[c] = reconstructAllTargets(runs[c], grey, ws, result);
    if (ok(frame.status[c])) frame.status[c] = measureTwoTargets(result, frame.measurement[c]);
  }
}

void summariseTwoTargets(TwoTargetStudyResult& result) {
  result.summaries.clear();
  result.failures.clear();
  std::vector<double> distance, angle;
  bool measured = false;
  for (std::size_t begin = 0; begin < result.frames.size();) {
    const int position = result.frames[begin].position;
    std::size_t end = begin;
    while (end < result.frames.size() && result.frames[end].position == position) ++end;
    for (int c = 0; c < kCorrections; ++c) {
      distance.clear();
      angle.clear();
      for (std::size_t i = begin; i < end; ++i) {
        const TwoTargetFrame& f = result.frames[i];
        if (!ok(f.status[c])) continue;
        distance.push_back(f.measurement[c].distance_mm - result.object.spacing_mm);
        angle.push_back(f.measurement[c].angle_deg - result.object.angle_deg);
      }
      measured = measured || !distance.empty();
      result.summaries.push_back(TwoTargetSummary{position, kCorrectionOn[c], static_cast<int>(end - begin),
                                                  summarizeErrors(distance), summarizeErrors(angle)});
    }
    begin = end;
  }
  for (const TwoTargetFrame& f : result.frames)
    for (const Status s : f.status) {
      if (ok(s)) continue;
      auto it = std::find_if(result.failures.begin(), result.failures.end(), [&](const auto& r) { return r.first == s; });
      if (it == result.failures.end())
        result.failures.emplace_back(s, 1);
      else
        ++it->second;
    }
  std::stable_sort(result.failures.begin(), result.failures.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  if (measured) {
    result.status = Status::Ok;
    result.error.clear();
  } else if (result.frames.empty() || result.failures.empty()) {
    result.status = Status::TooFewFrames;
    result.error = inWords(result.status) + " (no frame analysed)";
  } else {
    result.status = result.failures.front().first;
    result.error = inWords(result.status) + " (no frame of " + std::to_string(result.frames.size()) +
                   " gave both targets)";
  }
}

TwoTargetStudyResult runVirtualTwoTargets(const Settings& settings, const VirtualTwoTargetParams& params,
                                          StudyProgress& progress) {
  TwoTargetStudyResult result;
  result.object = params.object;
  Settings s = settings;
  if (params.thesis_lens) s.camera.distortion = kThesisCameraDistortion;
  s.virtual_scene.noise_sigma = params.noise_sigma;
  if (!twoTargetObjectFits(params.object, s.virtual_scene.card_size_mm)) {
    result.status = Status::InvalidSettings;
    result.error = "the cards do not fit on the faces: each target centre must lie at least half a card (" +
                   std::to_string(static_cast<int>(0.5 * s.virtual_scene.card_size_mm)) +
                   " mm) from the edge between the faces, and the angle must lie between 0 and 180 degrees";
    return result;
  }
  std::vector<int> positions = {1, 2, 3};
  if (params.position >= 1 && params.position <= 3) positions = {params.position};
  const int frames = std::max(1, params.frames_per_position);
  progress.total.store(frames * static_cast<int>(positions.size()));

  TwoTargetMeasurer measurer(s);
  TwoTargetRenderWorkspace render_ws;
  cv::Mat image;
  result.frames.reserve(static_cast<std::size_t>(progress.total.load()));
  for (const int position : positions) {
    const Pose object_pose = twoTargetStudyPosition(position);
    for (int i = 0; i < frames; ++i) {
      if (progress.cancel.load()) {
        result.status = Status::Stopped;
        result.error = "cancelled";
        return result;
      }
      // The thesis's order: natural light for the first half, extra lights for the second.
      VirtualSceneOptions scene = s.virtual_scene;
      applyStudyLighting(i < frames / 2 ? StudyLighting::Natural : StudyLighting::Extra, scene);
      renderTwoTargets(s.camera, s.target, scene, params.object, object_pose, image,
                       static_cast<std::uint64_t>(result.frames.size()), render_ws);
      TwoTargetFrame f;
      f.index = static_cast<std::int64_t>(result.frames.size());
      f.position = position;
      measurer.measure(image, f);
      result.frames.push_back(f);
      progress.done.store(static_cast<int>(result.frames.size()));
    }
  }
  summariseTwoTargets(result);
  return result;
}

}  // namespace imagepro::app
