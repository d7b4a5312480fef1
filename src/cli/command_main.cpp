#include <cstdio>
#include <cstring>
#include <exception>
#include <opencv2/core/utils/logger.hpp>

#include "cli/command.h"
#include "core/common/data_directory.h"
#include "core/common/version.h"

namespace imagepro::cli {

namespace {

void printOverview(const char* program, const char* summary) {
  std::printf(
      "%s: %s\n\n"
      "Usage: %s COMMAND [options]   (%s COMMAND --help for details)\n"
      "  or:  %s --help|--version|--data-dir\n\n"
      "Commands:\n",
      program, summary, program, program, program);
  for (const auto& [name, command] : commands()) std::printf("  %-14s %s\n", name.c_str(), command.summary.c_str());
  std::printf(
      "\nEvery command takes --config FILE (the settings JSON; defaults otherwise).\n\n"
      "Options:\n"
      "  --help         this overview\n"
      "  --version      print the version\n"
      "  --data-dir     print the folder of the shipped data: the default settings.json,\n"
      "                 the sample frames (samples/) and, installed, the printable patterns\n"
      "                 (patterns/)\n");
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
  if (std::strcmp(argv[1], "--version") == 0) {
    std::printf("%s %s\n", program, kVersion);
    return 0;
  }
  if (std::strcmp(argv[1], "--data-dir") == 0) {
    const auto dir = dataDirectory();
    if (dir.empty()) {
      std::fprintf(stderr,
                   "%s: no data folder: settings.json is neither installed beside the program nor in the sources it "
                   "was built from\n",
                   program);
      return 1;
    }
    std::printf("%s\n", dir.c_str());
    return 0;
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
