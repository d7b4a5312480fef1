#pragma once
// Command-line options that name an option enum's value: parsed by the key of the
// enum's table (core/settings/enum_names.h), and listed in --help with each value's
// display name and description from the same table.
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "cli/command.h"
#include "core/settings/enum_names.h"

namespace imagepro::cli {

// --key's value as one of E's keys (kept by `keep`, when given), or `fallback` when
// --key is not given; anything else is a UsageError listing the keys.
template <class E>
E enumOption(const Args& args, const std::string& key, E fallback, std::type_identity_t<std::function<bool(E)>> keep = {}) {
  const auto name = args.value(key);
  if (!name) return fallback;
  const auto value = parseEnum<E>(*name);
  if (!value || (keep && !keep(*value))) {
    std::string keys;
    for (const auto& e : enumEntries(E{}))
      if (!keep || keep(e.value)) keys += (keys.empty() ? "" : ", ") + std::string(e.key);
    throw UsageError("--" + key + ": \"" + *name + "\" is not one of " + keys);
  }
  return *value;
}

// One row a value: "    key  Label: description", wrapped to the help's width.
std::string choicesHelp(const std::vector<SettingKey::Choice>& rows);

template <class E>
std::string choicesHelp(std::function<bool(E)> keep = {}) {
  std::vector<SettingKey::Choice> rows;
  for (const auto& e : enumEntries(E{}))
    if (!keep || keep(e.value)) rows.push_back({e.key, e.label, e.description});
  return choicesHelp(rows);
}

}  // namespace imagepro::cli
