#pragma once
// The one place the application knows the concrete frame sources: builds the source
// the Input Source panel names, passes it new settings and the appendix A keys.
#include <QStringList>

#include <memory>
#include <string>

#include "app/source_kind.h"
#include "core/settings/settings.h"
#include "core/source/source.h"
#include "core/source/virtual_motion.h"

namespace imagepro::app {

// nullptr with `error` (naming the file or device and the reason) when it cannot be built.
// For File, `paths` are image files, folders (every image in natural order), list files,
// or one video file (played at its own rate).
std::unique_ptr<FrameSource> createSource(SourceKind kind, const Settings& settings, const QStringList& paths,
                                          std::string& error);
// Gives a live source the new settings (the virtual scene and camera; its time and
// key offset are kept). Files and cameras take nothing from the settings.
void updateSource(FrameSource& source, SourceKind kind, const Settings& settings);
// Moves the virtual target by one key press; other sources ignore keys.
void pressSourceKey(FrameSource& source, SourceKind kind, VirtualKey key);

}  // namespace imagepro::app
