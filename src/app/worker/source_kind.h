#pragma once
// The three input sources of the Input Source panel (thesis appendix A, 2.2): core's
// SourceKind with the panel's words.
#include <QString>

#include "core/settings/options.h"

namespace imagepro::app {

// A step through the File source's open image list.
enum class FileStep { First, Previous, Next, Last };

// Panel label and command-line name ("file", "camera", "virtual").
QString sourceKindLabel(SourceKind kind);
QString sourceKindName(SourceKind kind);
bool parseSourceKind(const QString& name, SourceKind& out);

}  // namespace imagepro::app
