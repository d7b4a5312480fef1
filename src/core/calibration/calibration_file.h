#pragma once
// The calibration file: what the lens distortion calibration (thesis 4.6) leaves behind for
// later runs. It is the settings JSON (docs/conventions.md) with only the camera of the
// source in use, carrying the distortion found ({"cameras": {"file": {...}}}), so any
// settings reader takes it and binds it to that source (the keys it lacks keep their values):
// `imagepro-cli --config FILE`, the application's Load Settings. Written by the CLI's
// calibrate command and by the application's calibration wizard.
#include <string>

#include "core/settings/settings.h"

namespace imagepro {

// The file's text: {"cameras": {"<settings.source>": {...}}}, indented, with a final newline.
std::string calibrationFileJson(const Settings& settings);

// Writes calibrationFileJson(settings) to `path` atomically (core/common/atomic_file.h): a file
// already there is kept as "<path>.bak", and on failure the old file is untouched. False with
// `error` naming the file and the reason.
bool writeCalibrationFile(const std::string& path, const Settings& settings, std::string& error);

}  // namespace imagepro
