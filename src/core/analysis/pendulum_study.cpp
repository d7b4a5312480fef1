#include "core/analysis/pendulum_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/analysis/frame_limit.h"
#include "core/analysis/pose_series.h"
#include "core/camera/video_file.h"
#include "core/pipeline/engine.h"
#include "core/source/image_inputs.h"
#include "core/source/sources.h"
#include "core/source/virtual_motion.h"

namespace imagepro {

namespace {

std::string inWords(Status s) { return std::string(statusName(s)) + ": " + std::string(statusMessage(s)); }

void fail(PendulumStudyResult& result, Status status, std::string error) {
  result.status = status;
  result.error = std::move(error);
}

// One recording's frames reconstructed and timed.
struct Recording {
  std::vector<PoseSample> samples;
  std::vector<std::string> unreadable;
  Status status = Status::Ok;  // of reading it
  std::string error;
};

// Every frame of `source` reconstructed by an engine of `settings`, timed by
// retimeSamples (counts reported from `done_before` on).
Recording reconstructRecording(FrameSource& source, const Settings& settings, double rate_hz,
                               const StudyCallbacks& callbacks, const FrameResultSink& sink, int done_before = 0) {
  Recording rec;
  Engine engine(settings);
  FrameResult r;
  std::vector<std::int64_t> indices;
  Status first_unreadable = Status::Ok;
  for (;;) {
    if (callbacks.cancelRequested()) {
      rec.status = Status::Stopped;
      rec.error = "cancelled";
      return rec;
    }
    const Status grabbed = engine.step(source, r);
    if (grabbed == Status::EndOfStream) break;
    if (!ok(grabbed)) {
      if (rec.unreadable.empty()) first_unreadable = grabbed;
      const std::string reason = source.lastError();
      const std::string frame = r.name.empty() ? std::to_string(r.index) : r.name;
      rec.unreadable.push_back(reason.empty() ? frame + ": " + inWords(grabbed) : reason);
    }
    PoseSample s;
    s.t_s = r.timestamp_s;
    s.valid = ok(r.status) && r.pose.has_value();
    if (s.valid) s.pose = *r.pose;
    rec.samples.push_back(s);
    indices.push_back(r.index);
    if (sink) sink(r);
    callbacks.report(done_before + static_cast<int>(rec.samples.size()), 0);
  }
  // Nothing could be read (a missing file, say): that is the answer, not the analysis's.
  if (!rec.samples.empty() && rec.unreadable.size() == rec.samples.size()) {
    rec.status = first_unreadable;
    rec.error = std::string(statusName(first_unreadable)) + ": " + rec.unreadable.front();
    if (rec.unreadable.size() > 1)
      rec.error += " (and " + std::to_string(rec.unreadable.size() - 1) + " more frames that could not be read)";
    return rec;
  }
  if (!retimeSamples(rec.samples, indices, rate_hz)) {
    rec.status = Status::InvalidSettings;
    rec.error = "the frames have no times: give a frame rate";
  }
  return rec;
}

// A recording named by its path: a pose CSV, a video, or images.
Recording readRecording(const std::string& path, const Settings& settings, double rate_hz,
                        const StudyCallbacks& callbacks, int done_before) {
  Recording rec;
  if (std::filesystem::path(path).extension() == ".csv") {
    rec.status = readPoseSeries(path, rate_hz, rec.samples, rec.error);
    if (!ok(rec.status)) rec.error = std::string(statusName(rec.status)) + ": " + rec.error;
    return rec;
  }
  std::unique_ptr<FrameSource> source;
  if (isVideoFileName(path)) {
    auto video = std::make_unique<VideoFileSource>(path, VideoPacing::AsFastAsPossible);
    if (const Status s = video->open(); !ok(s)) {
      rec.status = s;
      rec.error = std::string(statusName(s)) + ": " + video->lastError();
      return rec;
    }
    source = std::move(video);
  } else {
    std::vector<std::string> paths;
    for (ImageInput& input : expandImageInputs({path})) {
      if (!ok(input.status)) {
        rec.status = input.status;
        rec.error = std::string(statusName(input.status)) + ": " + input.error;
        return rec;
      }
      paths.push_back(std::move(input.path));
    }
    source = makeFileSource(std::move(paths));
  }
  return reconstructRecording(*source, settings, rate_hz, callbacks, {}, done_before);
}

// The recording's samples and frames that could not be read moved into `result`
// (the still's named as such); false, with the result failed, when it could not be read.
bool take(Recording&& rec, const char* name, bool still, PendulumStudyResult& result) {
  for (std::string& u : rec.unreadable) result.unreadable.push_back(name ? std::string(name) + ": " + u : u);
  (still ? result.still_samples : result.samples) = std::move(rec.samples);  // kept when cancelled too
  if (!ok(rec.status)) {
    fail(result, rec.status, name ? std::string(name) + ": " + rec.error : rec.error);
    return false;
  }
  return true;
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

double standardDeviation(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double sum = 0.0;
  for (double x : v) sum += (x - m) * (x - m);
  return std::sqrt(sum / static_cast<double>(v.size() - 1));
}

}  // namespace

void analysePendulumSamples(PendulumStudyResult& result) {
  result.analysis = PendulumAnalysis{};
  result.status = result.has_still
                      ? analyzePendulumStillSwing(result.still_samples, result.samples, result.options, result.analysis)
                      : analyzePendulum(result.samples, result.options, result.analysis);
  result.error.clear();
  if (ok(result.status)) return;
  const PendulumAnalysis& a = result.analysis;
  if (a.still_failed)
    result.error = "still: " + inWords(result.status) + " (" + std::to_string(a.still_valid_frames) + " of " +
                   std::to_string(a.still_frames) + " frames with a pose; the length needs 4 in different places)";
  else
    result.error = (result.has_still ? "swing: " : "") + inWords(result.status) + " (" +
                   std::to_string(a.valid_frames) + " of " + std::to_string(result.samples.size()) +
                   " frames with a pose)";
  if (!result.unreadable.empty())
    result.error += "; " + std::to_string(result.unreadable.size()) + " of them could not be read, the first: " +
                    result.unreadable.front();
}

PendulumStudyResult runPendulumFile(const std::string& path, double rate_hz, const PendulumAnalysisOptions& options) {
  PendulumStudyResult result;
  result.options = options;
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
                                      const PendulumAnalysisOptions& options, const StudyCallbacks& callbacks,
                                      const FrameResultSink& sink) {
  PendulumStudyResult result;
  result.options = options;
  if (take(reconstructRecording(source, settings, rate_hz, callbacks, sink), nullptr, false, result))
    analysePendulumSamples(result);
  return result;
}

PendulumStudyResult runPendulumStillSwing(const std::string& still_path, const std::string& swing_path,
                                          const Settings& settings, double rate_hz,
                                          const PendulumAnalysisOptions& options, const StudyCallbacks& callbacks) {
  PendulumStudyResult result;
  result.options = options;
  result.has_still = true;
  if (!take(readRecording(still_path, settings, rate_hz, callbacks, 0), "still", true, result)) return result;
  const int done = static_cast<int>(result.still_samples.size());
  if (!take(readRecording(swing_path, settings, rate_hz, callbacks, done), "swing", false, result)) return result;
  analysePendulumSamples(result);
  return result;
}

PendulumStudyResult runVirtualPendulum(const Settings& settings, const VirtualPendulumParams& params,
                                       const StudyCallbacks& callbacks, const FrameResultSink& sink) {
  Settings s = settings;
  s.virtual_scene.noise_sigma = params.noise_sigma;
  if (params.rate_hz > 0.0) s.virtual_scene.frame_rate_hz = params.rate_hz;
  const int frames = std::max(0, params.frames);
  const int still_frames =
      params.still_recording ? std::max(0, params.still.positions) * std::max(1, params.still.frames_per_position) : 0;
  const int total = still_frames + frames;
  // The virtual source knows its length: the progress is reported against it.
  StudyCallbacks counted = callbacks;
  counted.progress = [&](int done, int) { callbacks.report(done, total); };
  callbacks.report(0, total);
  PendulumStudyResult result;
  result.options = params.options;
  result.has_still = params.still_recording;
  if (params.still_recording) {
    // The virtual pendulum jumps from one held angle to the next, where a real one is
    // carried between them: each still frame is searched whole, not tracked.
    Settings whole = s;
    whole.pipeline.tracking.mode = TrackingMode::Off;
    PendulumStillSource still(whole, params.still);
    if (!take(reconstructRecording(still, whole, s.virtual_scene.frame_rate_hz, counted, {}), "still", true, result))
      return result;
  }
  PendulumSource pendulum(s, params.blur, params.interlaced);
  FrameLimit limited(pendulum, frames);
  if (take(reconstructRecording(limited, s, s.virtual_scene.frame_rate_hz, counted, sink, still_frames),
           params.still_recording ? "swing" : nullptr, false, result))
    analysePendulumSamples(result);
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  result.has_truth = true;
  result.truth = {truth.length_mm, pendulumPeriodS(truth), truth.gravity_m_s2};
  return result;
}

PendulumRunsSummary summarizePendulumRuns(std::span<const PendulumAnalysis> runs) {
  std::vector<double> length, period, g, g_plain;
  for (const PendulumAnalysis& a : runs) {
    length.push_back(a.length_mm);
    period.push_back(a.period_s);
    g.push_back(a.g_m_s2);
    g_plain.push_back(a.g_uncorrected_m_s2);
  }
  PendulumRunsSummary out;
  out.runs = static_cast<int>(runs.size());
  out.length_mm = mean(length);
  out.length_sd_mm = standardDeviation(length);
  out.period_s = mean(period);
  out.period_sd_s = standardDeviation(period);
  out.g_m_s2 = mean(g);
  out.g_sd_m_s2 = standardDeviation(g);
  out.g_uncorrected_m_s2 = mean(g_plain);
  out.g_uncorrected_sd_m_s2 = standardDeviation(g_plain);
  return out;
}

}  // namespace imagepro
