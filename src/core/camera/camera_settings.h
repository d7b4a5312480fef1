#pragma once
// The settings' Camera source section (CameraSourceOptions, options.h) applied to a
// camera: the capture request it describes, and its stored control values set on the
// device once it is open. The command line and the GUI open cameras through these, so
// a settings file means the same camera, size, rate and controls to both.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/camera/camera_source.h"
#include "core/settings/settings.h"

namespace imagepro {

// camera_source's device, rate, input and standard; its size, or the Camera source's
// camera model's (cameras.camera.width x height) when camera_source leaves it at 0.
CameraRequest cameraRequest(const Settings& settings);

// Sets one control, named by its key (or its name in any case), on `camera`, streaming
// or not. InvalidSettings when the device has no such control or refuses the value;
// `error` names the device and the control.
Status setControlByKey(CameraSource& camera, const std::string& key, std::int64_t value, std::string& error);

// Sets every stored control (key -> value) on `camera`, in the device's order; one that
// is refused is tried once more after the others (a manual exposure time needs the
// automatic exposure off first). A control the device lacks or refuses in the end is
// one line in `problems`; the others are set all the same.
void applyStoredControls(CameraSource& camera, const std::map<std::string, std::int64_t>& controls,
                         std::vector<std::string>& problems);

}  // namespace imagepro
