// imagepro-cli: the ImagePro pipeline without a window. Each subcommand is in its
// own cmd_<name>.cpp; this file only dispatches and turns errors into one line.
#include <cstdio>
#include <cstring>
#include <exception>
#include <opencv2/core/utils/logger.hpp>

#include "cli/command.h"

using imagepro::cli::Args;
using imagepro::cli::commands;

namespace {

void printOverview() {
  std::printf(
      "imagepro-cli: headless ImagePro, monocular 3D pose of a circular target\n\n"
      "usage: imagepro-cli COMMAND [options]   (imagepro-cli COMMAND --help for details)\n\n"
      "commands:\n");
  for (const auto& [name, command] : commands()) std::printf("  %-14s %s\n", name.c_str(), command.summary.c_str());
  std::printf("\nEvery command takes --config FILE (the settings JSON; defaults otherwise).\n");
}

}  // namespace

int main(int argc, char** argv) {
  // Every problem is reported once, as our own line; OpenCV's log would add its own.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0 ||
      std::strcmp(argv[1], "help") == 0) {
    printOverview();
    return argc < 2 ? 2 : 0;
  }
  const auto it = commands().find(argv[1]);
  if (it == commands().end()) {
    std::fprintf(stderr, "imagepro-cli: unknown command \"%s\" (imagepro-cli --help lists them)\n", argv[1]);
    return 2;
  }
  const auto& command = it->second;
  try {
    const Args args(argc - 2, argv + 2, command.flags);
    if (args.has("help")) {
      std::printf("%s\n", command.usage.c_str());
      return 0;
    }
    return command.run(args);
  } catch (const imagepro::cli::UsageError& e) {
    std::fprintf(stderr, "imagepro-cli %s: %s (see --help)\n", argv[1], e.what());
    return 2;
  } catch (const imagepro::cli::InputError& e) {
    std::fprintf(stderr, "imagepro-cli %s: %s\n", argv[1], e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "imagepro-cli %s: %s\n", argv[1], e.what());
    return 1;
  }
}
