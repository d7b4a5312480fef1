#pragma once
// The distance and angle case study (thesis 5.3.1) as a whole run: every frame of the
// virtual object of fig. 5.2 (or of any frame source) has both its targets
// reconstructed, with and without distortion correction, and the distance between
// their centres and the angle between their normals are compared with the object's
// known values, per position. The CLI's `two-targets` and the Analysis window both
// call these, with progress and cancellation.
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/error_summary.h"
#include "core/analysis/multi_target.h"
#include "core/analysis/study_progress.h"
#include "core/analysis/two_targets.h"
#include "core/settings/settings.h"
#include "core/source/source.h"

namespace imagepro {

// Each frame is measured twice: with and without distortion correction.
inline constexpr int kCorrections = 2;
inline constexpr bool kCorrectionOn[kCorrections] = {true, false};

struct TwoTargetFrame {
  std::int64_t index = 0;
  std::string name;                      // the file's, when the frame is one
  std::string error;                     // why the source could not give the frame
  int position = 0;                      // virtual object position 1..3, 0 for other frames
  std::optional<StudyLighting> lighting;  // of a virtual frame
  Status status[kCorrections] = {Status::Stopped, Status::Stopped};
  TwoTargetMeasurement measurement[kCorrections];
};

// Errors of one position (or of all other frames) with or without correction.
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
  std::vector<TwoTargetSummary> summaries;        // per position, corrected then not
  std::vector<std::pair<Status, int>> failures;  // why measurements failed, with counts, commonest first
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

// The virtual object at the study positions, half the frames of each in natural light
// and half with extra lights (a cancelled run: Stopped; an object whose cards do not
// fit on its faces: InvalidSettings).
TwoTargetStudyResult runVirtualTwoTargets(const Settings& settings, const VirtualTwoTargetParams& params,
                                          const StudyCallbacks& callbacks);

// Every frame of `source` measured (a frame the source cannot give keeps its status and
// reason); a cancelled run: Stopped.
TwoTargetStudyResult runTwoTargetSource(FrameSource& source, const Settings& settings, const TwoTargetObject& object,
                                        const StudyCallbacks& callbacks);

}  // namespace imagepro
