#pragma once
// The three input sources of the Input Source panel (thesis appendix A, 2.2).
#include <QString>

#include <array>

namespace imagepro::app {

enum class SourceKind { File, Camera, Virtual };

inline constexpr std::array<SourceKind, 3> kSourceKinds{SourceKind::File, SourceKind::Camera, SourceKind::Virtual};

// Panel label and command-line name ("file", "camera", "virtual").
QString sourceKindLabel(SourceKind kind);
QString sourceKindName(SourceKind kind);
bool parseSourceKind(const QString& name, SourceKind& out);

}  // namespace imagepro::app
