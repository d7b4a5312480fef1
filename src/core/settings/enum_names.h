#pragma once
// The names of every option enum as they appear in the settings file, on the CLI
// and in the GUI's lists: one table per enum, used for both directions.
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/settings/options.h"

namespace imagepro {

template <class E>
struct EnumEntry {
  E value;
  std::string_view name;
};

std::span<const EnumEntry<ThresholdMethod>> enumEntries(ThresholdMethod);
std::span<const EnumEntry<Binarization>> enumEntries(Binarization);
std::span<const EnumEntry<EdgeMethod>> enumEntries(EdgeMethod);
std::span<const EnumEntry<ConnectivityMethod>> enumEntries(ConnectivityMethod);
std::span<const EnumEntry<EllipseMethod>> enumEntries(EllipseMethod);
std::span<const EnumEntry<FitAcceptRule>> enumEntries(FitAcceptRule);
std::span<const EnumEntry<ContourMode>> enumEntries(ContourMode);
std::span<const EnumEntry<TrackingMode>> enumEntries(TrackingMode);
std::span<const EnumEntry<ApplicationLevel>> enumEntries(ApplicationLevel);
std::span<const EnumEntry<DisplayOptions::Background>> enumEntries(DisplayOptions::Background);
std::span<const EnumEntry<DisplayOptions::Edges>> enumEntries(DisplayOptions::Edges);
std::span<const EnumEntry<DisplayOptions::Target>> enumEntries(DisplayOptions::Target);
std::span<const EnumEntry<RenderMode>> enumEntries(RenderMode);
std::span<const EnumEntry<MotionKind>> enumEntries(MotionKind);
std::span<const EnumEntry<PoseAxis>> enumEntries(PoseAxis);

template <class E>
std::string_view enumName(E value) {
  for (const auto& e : enumEntries(E{}))
    if (e.value == value) return e.name;
  return "?";
}

template <class E>
std::optional<E> parseEnum(std::string_view name) {
  for (const auto& e : enumEntries(E{}))
    if (e.name == name) return e.value;
  return std::nullopt;
}

// "a, b, c": the accepted names, for error messages and --help.
template <class E>
std::string enumChoices() {
  std::string out;
  for (const auto& e : enumEntries(E{})) {
    if (!out.empty()) out += ", ";
    out += e.name;
  }
  return out;
}

}  // namespace imagepro
