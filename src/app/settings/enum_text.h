#pragma once
// The GUI's text of the option enums, from their one table (core/settings/enum_names.h):
// lists show the display name ("AT-Mod"), tooltips add the description.
#include <QString>

#include <string_view>

#include "core/settings/enum_names.h"

namespace imagepro::app {

inline QString fromView(std::string_view text) {
  return QString::fromUtf8(text.data(), static_cast<qsizetype>(text.size()));
}

// "AT-Mod: the same minimum error criterion ...": an enum value's tooltip.
template <class E>
QString entryToolTip(const EnumEntry<E>& entry) {
  return fromView(entry.label) + QStringLiteral(": ") + fromView(entry.description);
}

// "AT-Mod": the display name of `value`.
template <class E>
QString labelOf(E value) {
  return fromView(enumLabel(value));
}

}  // namespace imagepro::app
