// The calibration file, {"cameras": {"<source>": {...}}} (or an older file's one
// {"camera": {...}}), read by the settings reader, as the CLI's
// --config and the application's Load Settings read it. A camera it accepts must write
// back to the same file, and its lens model must undistort points without failing.
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/calibration/calibration_file.h"
#include "core/reconstruction/undistort.h"
#include "core/settings/settings.h"
#include "fuzz_support.h"

using namespace imagepro;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::scratchFile("calibration.json", data, size);
  Settings settings;
  std::string error;
  if (loadSettings(path, settings, error) != Status::Ok) {
    if (error.empty()) fuzz::fail("a refused calibration file names no reason", "");
    return 0;
  }
  const std::string written = calibrationFileJson(settings);
  Settings again;
  if (settingsFromJson(written, again, error) != Status::Ok)
    fuzz::fail("a written calibration file does not load", error + "\n" + written);
  if (calibrationFileJson(again) != written) fuzz::fail("a written calibration file loads as another camera", written);

  // The corners, the centre and an edge midpoint of the image, both undistortions.
  const CameraModel& cam = settings.camera();
  const double w = cam.width - 1.0, h = cam.height - 1.0;
  const std::array<Eigen::Vector2d, 4> corners{Eigen::Vector2d(0, 0), Eigen::Vector2d(w, h),
                                               Eigen::Vector2d(0.5 * w, 0.5 * h), Eigen::Vector2d(w, 0.5 * h)};
  for (bool exact : {false, true}) {
    std::vector<Eigen::Vector2d> points(corners.begin(), corners.end());
    undistortPoints(cam, exact, points);
  }
  return 0;
}
