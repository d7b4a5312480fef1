#include "core/analysis/two_target_study.h"

#include <algorithm>


namespace imagepro {

namespace {

std::string inWords(Status s) { return std::string(statusName(s)) + ": " + std::string(statusMessage(s)); }

void countFailures(TwoTargetStudyResult& result) {
  result.failures.clear();
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
}

TwoTargetStudyResult cancelled(TwoTargetStudyResult& result) {
  result.status = Status::Stopped;
  result.error = "cancelled";
  return std::move(result);
}

}  // namespace

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
  countFailures(result);
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
                                          const StudyCallbacks& callbacks) {
  TwoTargetStudyResult result;
  result.object = params.object;
  Settings s = settings;
  if (params.thesis_lens) s.camera().distortion = kThesisCameraDistortion;
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
  const int total = frames * static_cast<int>(positions.size());
  callbacks.report(0, total);

  TwoTargetMeasurer measurer(s);
  TwoTargetRenderWorkspace render_ws;
  cv::Mat image;
  result.frames.reserve(static_cast<std::size_t>(total));
  for (const int position : positions) {
    const Pose object_pose = twoTargetStudyPosition(position);
    for (int i = 0; i < frames; ++i) {
      if (callbacks.cancelRequested()) return cancelled(result);
      // The thesis's order: natural light for the first half, extra lights for the second.
      const StudyLighting lighting = i < frames / 2 ? StudyLighting::Natural : StudyLighting::Extra;
      VirtualSceneOptions scene = s.virtual_scene;
      applyStudyLighting(lighting, scene);
      renderTwoTargets(s.camera(), s.target, scene, params.object, object_pose, image,
                       static_cast<std::uint64_t>(result.frames.size()), render_ws);
      TwoTargetFrame f;
      f.index = static_cast<std::int64_t>(result.frames.size());
      f.position = position;
      f.lighting = lighting;
      measurer.measure(image, f);
      result.frames.push_back(std::move(f));
      callbacks.report(static_cast<int>(result.frames.size()), total);
    }
  }
  summariseTwoTargets(result);
  return result;
}

TwoTargetStudyResult runTwoTargetSource(FrameSource& source, const Settings& settings, const TwoTargetObject& object,
                                        const StudyCallbacks& callbacks) {
  TwoTargetStudyResult result;
  result.object = object;
  TwoTargetMeasurer measurer(settings);
  Frame frame;
  for (;;) {
    if (callbacks.cancelRequested()) return cancelled(result);
    const Status s = source.next(frame);
    if (s == Status::EndOfStream) break;
    TwoTargetFrame f;
    f.index = frame.index;
    f.name = frame.name;
    if (ok(s)) {
      measurer.measure(frame.image, f);
    } else {
      f.status[0] = f.status[1] = s;
      f.error = source.lastError();
    }
    result.frames.push_back(std::move(f));
    callbacks.report(static_cast<int>(result.frames.size()), 0);
  }
  summariseTwoTargets(result);
  return result;
}

}  // namespace imagepro
