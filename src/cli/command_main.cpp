#include <cstdio>
#include <cstring>
#include <exception>
#include <opencv2/core/utils/logger.hpp>

#include "cli/command.h"

namespace imagepro::cli {

namespace {

void printOverview(const char* program, const char* summary) {
  std::printf(
      "%s: %s\n\n"
      "usage: %s COMMAND [options]   (%s COMMAND --help for details)\n\n"
      "commands:\n",
      program, summary, program, program);
  for (const auto& [name, command] : commands()) std::printf("  %-14s %s\n", name.c_str(), command.summary.c_str());
  std::printf("\nEvery command takes --config FILE (the settings JSON; defaults otherwise).\n");
}

}  // namespace

int runCommands(const char* program, const char* summary, int argc, char** argv) {
  // Every problem is reported once, as our own line; OpenCV's log would add its own.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0 ||
      std::strcmp(argv[1], "help") == 0) {
    printOverview(program, summary);
    return argc < 2 ? 2 : 0;
  }
  const auto it = commands().find(argv[1]);
  if (it == commands().end()) {
    std::fprintf(stderr, "%s: unknown command \"%s\" (%s --help lists them)\n", program, argv[1], program);
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
  } catch (const UsageError& e) {
    std::fprintf(stderr, "%s %s: %s (see --help)\n", program, argv[1], e.what());
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s %s: %s\n", program, argv[1], e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s %s: %s\n", program, argv[1], e.what());
    return 1;
  }
}

}  // namespace imagepro::cli
