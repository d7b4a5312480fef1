#pragma once
// The pendulum and g case study (thesis 5.3.2) as a whole run: poses collected from a
// data-out CSV, from any frame source reconstructed frame by frame, or from the
// virtual pendulum, timed, then analysed by analyzePendulum (pendulum.h); or, as the
// thesis ran it, two recordings: the length from a "still" one and the period from a
// "swing" one (analyzePendulumStillSwing). The CLI's `pendulum` and the Analysis
// window both call these, with progress and cancellation.
#include <span>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/analysis/pendulum.h"
#include "core/analysis/pendulum_scene.h"
#include "core/analysis/study_progress.h"
#include "core/pipeline/frame_result.h"
#include "core/settings/settings.h"
#include "core/source/source.h"

namespace imagepro {

struct PendulumTruth {
  double length_mm = 0.0, period_s = 0.0, g_m_s2 = 0.0;
};

struct PendulumStudyResult {
  Status status = Status::Stopped;  // of reading the input, then of analyzePendulum
  std::string error;                // the problem in words when status is not Ok
  std::vector<PoseSample> samples;       // the swing
  std::vector<PoseSample> still_samples;  // the still recording, when the length comes from one
  bool has_still = false;
  std::vector<std::string> unreadable;  // "frame: reason" of each frame the source could not give
  PendulumAnalysisOptions options;
  PendulumAnalysis analysis;
  bool has_truth = false;  // the virtual pendulum's own length, period and g
  PendulumTruth truth;
};

struct VirtualPendulumParams {
  int frames = 250;          // imagepro-cli pendulum --virtual's defaults
  double noise_sigma = 3.0;  // grey levels
  double rate_hz = 0.0;      // frames per second; 0: the settings' virtual frame rate
  MotionBlur blur;
  bool interlaced = false;        // two fields at different instants (pendulum_scene.h)
  bool still_recording = false;   // the length from the pendulum held still (`still`)
  PendulumStillParams still;
  PendulumAnalysisOptions options;
};

// Called with every reconstructed frame (to write it as data out, say).
using FrameResultSink = std::function<void(const FrameResult&)>;

// Analyses `result.samples` (and `still_samples` when has_still; status, error and
// analysis filled in). A failed analysis with unreadable frames names the first of
// them and its reason.
void analysePendulumSamples(PendulumStudyResult& result);

// A data-out (or reconstruct) CSV; rows without timestamp_s take frame / rate_hz.
PendulumStudyResult runPendulumFile(const std::string& path, double rate_hz, const PendulumAnalysisOptions& options);

// Frames' own times (samples[i].t_s) are kept when they increase; otherwise (image
// files) frame i is at indices[i] / rate_hz. False when they do not increase and
// rate_hz is not above 0.
bool retimeSamples(std::vector<PoseSample>& samples, const std::vector<std::int64_t>& indices, double rate_hz);

// Every frame of `source` reconstructed by an engine of `settings`, timed by
// retimeSamples, then analysed (a cancelled run: Stopped; frames without times and
// no rate: InvalidSettings; no frame that could be read: the status and reason of
// the first, FileNotFound say).
PendulumStudyResult runPendulumSource(FrameSource& source, const Settings& settings, double rate_hz,
                                      const PendulumAnalysisOptions& options, const StudyCallbacks& callbacks,
                                      const FrameResultSink& sink = {});

// The thesis's two recordings, each a pose CSV (by its .csv name), a video file, or
// images (a file, a folder, a list of paths) reconstructed by an engine of
// `settings`; frames without times are timed by rate_hz. A recording that cannot be
// read is named ("still: ..." or "swing: ...").
PendulumStudyResult runPendulumStillSwing(const std::string& still_path, const std::string& swing_path,
                                          const Settings& settings, double rate_hz,
                                          const PendulumAnalysisOptions& options, const StudyCallbacks& callbacks);

// The virtual pendulum of settings.virtual_scene.pendulum rendered and reconstructed
// frame by frame (after its still recording when params.still_recording), with its
// true length, period and g.
PendulumStudyResult runVirtualPendulum(const Settings& settings, const VirtualPendulumParams& params,
                                       const StudyCallbacks& callbacks, const FrameResultSink& sink = {});

// Several runs in one table, like thesis table 5.3: the mean and the standard
// deviation over the runs (0 for one run) of the length, the period and g.
struct PendulumRunsSummary {
  int runs = 0;
  double length_mm = 0.0, length_sd_mm = 0.0;
  double period_s = 0.0, period_sd_s = 0.0;
  double g_m_s2 = 0.0, g_sd_m_s2 = 0.0;
  double g_uncorrected_m_s2 = 0.0, g_uncorrected_sd_m_s2 = 0.0;  // eq. 5.1 with the measured period
};
PendulumRunsSummary summarizePendulumRuns(std::span<const PendulumAnalysis> runs);

}  // namespace imagepro
