#pragma once
// imagepro --camera DEV [--size WxH] [--fps F]: the Camera source's device, size and rate
// from the command line, over the settings' camera_source.
#include <QString>

#include "core/settings/options.h"

namespace imagepro::app {

// Sets `out`'s device, and its size and rate when `size` ("640x480") or `fps` are not
// empty. Another device than the stored one drops the stored controls (they were that
// device's). False with `error` naming the option for a malformed value; `out` is then
// unchanged.
bool applyCameraArguments(const QString& device, const QString& size, const QString& fps, CameraSourceOptions& out,
                          QString& error);

}  // namespace imagepro::app
