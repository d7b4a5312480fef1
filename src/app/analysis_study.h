#pragma once
// The two case studies of thesis 5.3 as the Analysis window runs them, without any
// widget: the pendulum and g (5.3.2) over a data-out CSV, poses collected from the
// live stream or the virtual pendulum; the distance and angle between two targets
// (5.3.1) over the virtual object or live frames. The algorithms are the analysis
// module's (src/core/analysis); these functions only drive them as imagepro-cli's
// pendulum and two-targets commands do, with progress and cancellation for a
// background thread.
#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "core/analysis/error_summary.h"
#include "core/analysis/multi_target.h"
#include "core/analysis/pendulum.h"
#include "core/analysis/two_targets.h"
#include "core/settings/settings.h"

namespace imagepro::app {

// Shared between the GUI thread and a study running on another thread.
struct StudyProgress {
  std::atomic<int> done{0};
  std::atomic<int> total{0};
  std::atomic<bool> cancel{false};
};

// ---- Pendulum and g (thesis 5.3.2) ---------------------------------------------

struct PendulumTruth {
  double length_mm = 0.0, period_s = 0.0, g_m_s2 = 0.0;
};

struct PendulumStudyResult {
  Status status = Status::Stopped;  // of reading the input, then of analyzePendulum
  std::string error;                // the problem in words when status is not Ok
  std::vector<imagepro::PoseSample> samples;
  bool amplitude_correction = true;
  PendulumAnalysis analysis;
  bool has_truth = false;  // the virtual pendulum's own length, period and g
  PendulumTruth truth;
};

struct VirtualPendulumParams {
  int frames = 250;           // imagepro-cli pendulum --virtual's defaults
  double noise_sigma = 3.0;   // grey levels
  bool amplitude_correction = true;
};

// Analyses `result.samples` (status, error and analysis filled in); Stopped when cancelled.
void analysePendulumSamples(PendulumStudyResult& result);

// A data-out (or reconstruct) CSV; rows without timestamp_s take frame / rate_hz.
PendulumStudyResult runPendulumFile(const std::string& path, double rate_hz, bool amplitude_correction);

// The virtual pendulum of settings.virtual_scene.pendulum rendered at the settings'
// frame rate and reconstructed by the engine frame by frame (a cancelled run: Stopped).
PendulumStudyResult runVirtualPendulum(const Settings& settings, const VirtualPendulumParams& params,
                                       StudyProgress& progress);

// Live frames: each one's time, pose (if any) and index. Times that do not increase
// (image files) are replaced by index / rate_hz.
void retimeSamples(std::vector<imagepro::PoseSample>& samples, const std::vector<std::int64_t>& indices,
                   double rate_hz);

// ---- Distance and angle between two targets (thesis 5.3.1) ----------------------

// Each frame is measured twice: with and without distortion correction.
inline constexpr int kCorrections = 2;
inline constexpr bool kCorrectionOn[kCorrections] = {true, false};

struct TwoTargetFrame {
  std::int64_t index = 0;
  int position = 0;  // virtual object position 1..3, 0 for live frames
  Status status[kCorrections] = {Status::Stopped, Status::Stopped};
  TwoTargetMeasurement measurement[kCorrections];
};

// Errors of one position (or of all live frames) with or without correction.
struct TwoTargetSummary {
  int position = 0;
  bool correction = true;
  int frames = 0;
  ErrorSummary distance_mm, angle_deg;  // measured - known
};

struct TwoTargetStudyResult {
  Status status = Status::Stopped;  // Ok when some frame gave both targets; else the commonest reason
  std::string error;                // in words when status is not Ok
  TwoTargetObject object;
  std::vector<TwoTargetFrame> frames;
  std::vector<TwoTargetSummary> summaries;           // per position, corrected then not
  std::vector<std::pair<Status, int>> failures;     // why measurements failed, with counts
};

struct VirtualTwoTargetParams {
  TwoTargetObject object;
  int frames_per_position = 40;  // imagepro-cli two-targets --virtual's defaults
  int position = 0;              // 1..3, or 0 for all three
  double noise_sigma = 2.0;
  bool thesis_lens = true;       // render and correct with the thesis camera's distortion
};

// The two runs' settings (with and without distortion correction) for `settings`.
struct TwoTargetMeasurer {
  explicit TwoTargetMeasurer(const Settings& settings);
  // Both runs on one grey frame.
  void measure(const cv::Mat& grey, TwoTargetFrame& frame);

  Settings runs[kCorrections];
  MultiTargetWorkspace ws;
  MultiTargetResult result;
};

// The summaries, failures, status and error of `result.frames`.
void summariseTwoTargets(TwoTargetStudyResult& result);

// The virtual object of thesis fig. 5.2 at the study positions, half the frames of
// each in natural light and half with extra lights (a cancelled run: Stopped;
// an object whose cards do not fit on its faces: InvalidSettings).
TwoTargetStudyResult runVirtualTwoTargets(const Settings& settings, const VirtualTwoTargetParams& params,
                                          StudyProgress& progress);

}  // namespace imagepro::app
