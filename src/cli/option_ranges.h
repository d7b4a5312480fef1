#pragma once
// Command-line options that set a value of the settings file accept exactly what the
// file does: the changed settings are written out and read back by the settings
// loader, so its ranges (written down once, in settings.cpp) apply, and NaN or
// infinity, which JSON cannot hold, is refused.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/settings/settings.h"

namespace imagepro::cli {

// A settings key (or the prefix of a group, "virtual.pose.") and the option that sets it.
using OptionKey = std::pair<std::string, std::string>;

// Throws UsageError naming the option (and the settings key) when `settings` would be
// refused by the settings loader.
void checkOptionRanges(const Settings& settings, const std::vector<OptionKey>& options);

// "0..255": the settings table's range of `key`, for --help and messages.
std::string rangeText(std::string_view key);
// A number as help texts print it (%g): a default quoted from the options' defaults.
std::string numberText(double v);

}  // namespace imagepro::cli
