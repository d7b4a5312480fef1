#pragma once
// imagepro-cli calibrate --intrinsics: the full intrinsic calibration
// (calibration/intrinsics.h) from images of a dot grid, with its quality report.
#include "cli/command.h"

namespace imagepro::cli {

int runIntrinsicCalibration(const Args& args);
extern const char* const kIntrinsicCalibrationUsage;

}  // namespace imagepro::cli
