#pragma once
// The one place the application knows the concrete frame sources: builds the source
// the Input Source panel names, passes it new settings and the appendix A keys.
#include <QStringList>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/worker/source_kind.h"
#include "core/settings/settings.h"
#include "core/source/source.h"
#include "core/source/virtual_motion.h"

namespace imagepro::app {

// nullptr with `error` (naming the file or device and the reason) when it cannot be built.
// For File, `paths` are image files, folders (every image in natural order) and list
// files, made one ImageListSource (image_list_source.h), or one video file (played at
// its own rate). For Camera, the settings' camera_source device, size and rate; its
// stored controls are set once it streams, and each one the device lacks or refuses is
// a line in `warnings` (the stream goes on).
std::unique_ptr<FrameSource> createSource(SourceKind kind, const Settings& settings, const QStringList& paths,
                                          std::string& error, std::vector<std::string>& warnings);
// Gives a live source the new settings in place (the virtual scene and camera; its time
// and key offset are kept). False when it cannot take them: a streaming camera asked for
// another device, size, rate, input or TV standard is to be opened anew. Files take
// nothing from the settings.
bool updateSource(FrameSource& source, SourceKind kind, const Settings& settings);
// Sets one control of the camera `device` now: through `source` when it is a camera
// streaming from that device, else on the device directly. Ok, or the named error.
Status setCameraControl(FrameSource* source, SourceKind kind, const std::string& device, const std::string& key,
                        std::int64_t value, std::string& error);
// Moves the virtual target by one key press; other sources ignore keys.
void pressSourceKey(FrameSource& source, SourceKind kind, VirtualKey key);

}  // namespace imagepro::app
