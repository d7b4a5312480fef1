#include "app/worker/source_kind.h"

#include "core/settings/enum_names.h"

namespace imagepro::app {

QString sourceKindLabel(SourceKind kind) { return QString::fromUtf8(enumLabel(kind).data(), enumLabel(kind).size()); }

QString sourceKindName(SourceKind kind) { return QString::fromUtf8(enumName(kind).data(), enumName(kind).size()); }

bool parseSourceKind(const QString& name, SourceKind& out) {
  const auto parsed = parseEnum<SourceKind>(name.toLower().toStdString());
  if (parsed) out = *parsed;
  return parsed.has_value();
}

}  // namespace imagepro::app
