#pragma once
// One table per option enum: for each value its key (in settings files and on the
// command line), its display name (the thesis's name, shown in the GUI's lists and
// the docs) and a one-line description (the GUI's tooltips, the CLI's --help and the
// user manual's method tables, `imagepro-cli settings --methods-markdown`).
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/settings/options.h"

namespace imagepro {

template <class E>
struct EnumEntry {
  E value;
  std::string_view key;          // settings files and the command line: "at-mod"
  std::string_view label;        // the GUI and the docs: "AT-Mod"
  std::string_view description;  // what it is, and where the thesis has it
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
std::span<const EnumEntry<Backdrop>> enumEntries(Backdrop);
std::span<const EnumEntry<MotionKind>> enumEntries(MotionKind);
std::span<const EnumEntry<PoseAxis>> enumEntries(PoseAxis);
std::span<const EnumEntry<StreamFormat>> enumEntries(StreamFormat);
std::span<const EnumEntry<SourceKind>> enumEntries(SourceKind);
std::span<const EnumEntry<TvStandard>> enumEntries(TvStandard);

// The value's row of its table; nullptr for a value outside it (a cast integer).
template <class E>
const EnumEntry<E>* enumEntry(E value) {
  for (const auto& e : enumEntries(E{}))
    if (e.value == value) return &e;
  return nullptr;
}

// The key of `value` ("at-mod"), as settings files and the command line spell it.
template <class E>
std::string_view enumName(E value) {
  const EnumEntry<E>* e = enumEntry(value);
  return e ? e->key : std::string_view("?");
}

// The display name of `value` ("AT-Mod").
template <class E>
std::string_view enumLabel(E value) {
  const EnumEntry<E>* e = enumEntry(value);
  return e ? e->label : std::string_view("?");
}

template <class E>
std::optional<E> parseEnum(std::string_view key) {
  for (const auto& e : enumEntries(E{}))
    if (e.key == key) return e.value;
  return std::nullopt;
}

// "a, b, c": the accepted keys, for error messages.
template <class E>
std::string enumChoices() {
  std::string out;
  for (const auto& e : enumEntries(E{})) {
    if (!out.empty()) out += ", ";
    out += e.key;
  }
  return out;
}

}  // namespace imagepro
