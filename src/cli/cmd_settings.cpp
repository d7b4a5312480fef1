// imagepro-cli settings: prints the effective settings JSON (the defaults, or
// --config FILE checked and completed with defaults), or writes it with --out.
#include <cstdio>

#include "cli/command.h"

namespace imagepro::cli {
namespace {

int run(const Args& args) {
  args.rejectUnknown({"out"});
  const Settings settings = loadConfig(args);
  const std::string text = settingsToJson(settings);
  if (const auto out = args.value("out")) {
    std::string error;
    if (!ok(saveSettings(*out, settings, error))) throw InputError(error);
    std::fprintf(stderr, "wrote %s\n", out->c_str());
  } else {
    std::fputs(text.c_str(), stdout);
  }
  return 0;
}

const CommandRegistration kRegistration{{
    "settings",
    "print or write the settings JSON (defaults, or --config checked and completed)",
    "usage: imagepro-cli settings [--config FILE] [--out FILE]\n\n"
    "Prints the effective settings: the defaults, or FILE with every missing key\n"
    "filled in. A malformed FILE is reported with the key at fault.\n"
    "  --out FILE   write to FILE (atomically) instead of printing",
    {},
    run,
}};

}  // namespace
}  // namespace imagepro::cli
