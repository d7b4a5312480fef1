#include "core/analysis/pendulum_study.h"

#include <algorithm>

#include "core/analysis/frame_limit.h"
#include "core/analysis/pose_series.h"
#include "core/pipeline/engine.h"
#include "core/source/virtual_motion.h"

namespace imagepro {

namespace {

std::string inWords(Status s) { return std::string(statusName(s)) + ": " + std::string(statusMessage(s)); }

void fail(PendulumStudyResult& result, Status status, std::string error) {
  result.status = status;
  result.error = std::move(error);
}

}  // namespace

void analysePendulumSamples(PendulumStudyResult& result) {
  PendulumAnalysisOptions options;
  options.amplitude_correction = result.amplitude_correction;
  result.analysis = PendulumAnalysis{};
  result.status = analyzePendulum(result.samples, options, result.analysis);
  result.error.clear();
  if (ok(result.status)) return;
  result.error = inWords(result.status) + " (" + std::to_string(result.analysis.valid_frames) + " of " +
                 std::to_string(result.samples.size()) + " frames with a pose)";
  if (!result.unreadable.empty())
    result.error += "; " + std::to_string(result.unreadable.size()) + " of them could not be read, the first: " +
                    result.unreadable.front();
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

bool retimeSamples(std::vector<PoseSample>& samples, const std::vector<std::int64_t>& indices, double rate_hz) {
  bool increasing = true;
  for (std::size_t i = 1; increasing && i < samples.size(); ++i) increasing = samples[i].t_s > samples[i - 1].t_s;
  if (increasing) return true;
  if (!(rate_hz > 0.0)) return false;
  for (std::size_t i = 0; i < samples.size() && i < indices.size(); ++i)
    samples[i].t_s = static_cast<double>(indices[i]) / rate_hz;
  return true;
}

PendulumStudyResult runPendulumSource(FrameSource& source, const Settings& settings, double rate_hz,
                                      bool amplitude_correction, const StudyCallbacks& callbacks,
                                      const FrameResultSink& sink) {
  PendulumStudyResult result;
  result.amplitude_correction = amplitude_correction;
  Engine engine(settings);
  FrameResult r;
  std::vector<std::int64_t> indices;
  Status first_unreadable = Status::Ok;
  for (;;) {
    if (callbacks.cancelRequested()) {
      fail(result, Status::Stopped, "cancelled");
      return result;
    }
    const Status grabbed = engine.step(source, r);
    if (grabbed == Status::EndOfStream) break;
    if (!ok(grabbed)) {
      if (result.unreadable.empty()) first_unreadable = grabbed;
      const std::string reason = source.lastError();
      const std::string frame = r.name.empty() ? std::to_string(r.index) : r.name;
      result.unreadable.push_back(reason.empty() ? frame + ": " + inWords(grabbed) : reason);
    }
    PoseSample s;
    s.t_s = r.timestamp_s;
    s.valid = ok(r.status) && r.pose.has_value();
    if (s.valid) s.pose = *r.pose;
    result.samples.push_back(s);
    indices.push_back(r.index);
    if (sink) sink(r);
    callbacks.report(static_cast<int>(result.samples.size()), 0);
  }
  // Nothing could be read (a missing file, say): that is the answer, not the analysis's.
  if (!result.samples.empty() && result.unreadable.size() == result.samples.size()) {
    fail(result, first_unreadable, std::string(statusName(first_unreadable)) + ": " + result.unreadable.front());
    if (result.unreadable.size() > 1)
      result.error += " (and " + std::to_string(result.unreadable.size() - 1) + " more frames that could not be read)";
    return result;
  }
  if (!retimeSamples(result.samples, indices, rate_hz)) {
    fail(result, Status::InvalidSettings, "the frames have no times: give a frame rate");
    return result;
  }
  analysePendulumSamples(result);
  return result;
}

PendulumStudyResult runVirtualPendulum(const Settings& settings, const VirtualPendulumParams& params,
                                       const StudyCallbacks& callbacks, const FrameResultSink& sink) {
  Settings s = settings;
  s.virtual_scene.noise_sigma = params.noise_sigma;
  if (params.rate_hz > 0.0) s.virtual_scene.frame_rate_hz = params.rate_hz;
  const int frames = std::max(0, params.frames);
  PendulumSource pendulum(s, params.blur);
  FrameLimit limited(pendulum, frames);
  // The virtual source knows its length: the progress is reported against it.
  StudyCallbacks counted = callbacks;
  counted.progress = [&](int done, int) { callbacks.report(done, frames); };
  callbacks.report(0, frames);
  PendulumStudyResult result =
      runPendulumSource(limited, s, s.virtual_scene.frame_rate_hz, params.amplitude_correction, counted, sink);
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  result.has_truth = true;
  result.truth = {truth.length_mm, pendulumPeriodS(truth), truth.gravity_m_s2};
  return result;
}

}  // namespace imagepro
