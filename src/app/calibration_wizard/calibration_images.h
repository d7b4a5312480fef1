#pragma once
// The images of the calibration wizard (thesis 4.6 step 1, appendix A.2.2) and what the
// procedure sees in each one before it runs: the target's detection and the pattern's pose
// (step 3), the spots' ideal positions (step 4), the spots found (step 5) and their matching
// (step 6), all with the estimate at zero (step 2), i.e. its first iteration. Plain
// functions, safe to run on any thread; the wizard runs them off the GUI thread.
#include <QString>

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "core/calibration/calibrate.h"
#include "core/calibration/spots.h"
#include "core/ellipse/ellipse.h"
#include "core/settings/settings.h"

namespace imagepro::app {

inline constexpr int kCalibrationSlots = 4;  // the thesis uses up to four images
// Where the virtual views put the pattern's target: on the optical axis, this far away.
inline constexpr double kVirtualCalibrationDistanceMm = 800.0;

struct CalibrationImage {
  cv::Mat grey;                     // CV_8UC1
  QString origin;                   // where it came from, in words
  cv::Size camera_size;             // the settings' camera it was analysed for
  Status target_status = Status::Stopped;  // the detection and reconstruction of the target
  std::optional<Ellipse> target;    // its outline, when detected
  Status spot_status = Status::Stopped;    // the spot finder's
  std::vector<ObservedSpot> spots;  // step 5
  CalibrationImageReport first;     // steps 3, 4 and 6 with zero distortion; first.status: the image's
};

// Reads an image file as 8-bit grey; FileNotFound or FileUnreadable with `error` naming the
// file and the reason.
Status readCalibrationImage(const QString& path, cv::Mat& grey, QString& error);

// The view of virtual slot 0-3 (thesis 4.6 step 1): the pattern turned +45 and -45 deg about
// x, then +45 and -45 deg about y, its target on the optical axis.
Pose virtualCalibrationView(int slot);
// The calibration pattern at that view, drawn by the Virtual source's renderer with the
// settings' camera (and so its distortion), target, pattern and virtual scene.
void renderVirtualCalibrationImage(const Settings& settings, int slot, cv::Mat& grey);

// Fills everything of `image` but grey and origin, with the settings' camera, target,
// pattern and pipeline options (the image's size must be the camera's: else InvalidSettings).
void analyseCalibrationImage(const Settings& settings, CalibrationImage& image);

// One line for the wizard: what the slot holds and what is wrong with it, in words.
// `run`: the image's report from the last calibration run, when there is one.
QString calibrationImageSummary(const CalibrationImage& image, const CalibrationImageReport* run);

}  // namespace imagepro::app
