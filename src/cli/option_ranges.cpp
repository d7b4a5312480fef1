#include "cli/option_ranges.h"

#include <cstdio>

#include "cli/command.h"

namespace imagepro::cli {

void checkOptionRanges(const Settings& settings, const std::vector<OptionKey>& options) {
  Settings reread;
  std::string error;
  if (ok(settingsFromJson(settingsToJson(settings), reread, error))) return;
  // error is "<key>: <problem>"; JSON writes NaN and infinity as null.
  const auto colon = error.find(": ");
  const std::string key = error.substr(0, colon);
  std::string problem = colon == std::string::npos ? error : error.substr(colon + 2);
  if (problem == "expected a number") problem = "expected a finite number";
  for (const auto& [prefix, option] : options)
    if (key.rfind(prefix, 0) == 0) throw UsageError(option + ": " + problem + " (as " + key + " in a settings file)");
  throw UsageError("the options give an invalid setting: " + error);
}

std::string numberText(double v) {
  char out[32];
  std::snprintf(out, sizeof out, "%g", v);
  return out;
}

std::string rangeText(std::string_view key) {
  const SettingKey* k = findSettingKey(key);
  if (!k) return "?";
  return numberText(k->lo) + ".." + numberText(k->hi);
}

}  // namespace imagepro::cli
