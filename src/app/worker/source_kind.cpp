#include "app/worker/source_kind.h"

namespace imagepro::app {

QString sourceKindLabel(SourceKind kind) {
  switch (kind) {
    case SourceKind::File: return QStringLiteral("File");
    case SourceKind::Camera: return QStringLiteral("Camera");
    case SourceKind::Virtual: return QStringLiteral("Virtual");
  }
  return {};
}

QString sourceKindName(SourceKind kind) { return sourceKindLabel(kind).toLower(); }

bool parseSourceKind(const QString& name, SourceKind& out) {
  for (SourceKind k : kSourceKinds) {
    if (sourceKindName(k) == name.toLower()) {
      out = k;
      return true;
    }
  }
  return false;
}

}  // namespace imagepro::app
