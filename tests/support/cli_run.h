// Runs imagepro-cli or imagepro-studies as a user would, for the tests of their
// commands: the exit code and what it printed on each stream.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/atomic_file.h"
#include "support/test_dirs.h"

namespace imagepro::test {

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

// Runs `program` with `args` (in the folder `cwd` when one is given), capturing stdout
// and stderr through files.
inline CliRun runProgram(const std::string& program, const std::string& args, const std::string& cwd = {}) {
  namespace fs = std::filesystem;
  // ctest runs the tests in parallel processes: each captures into files of its own.
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / ("cli_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  const std::string in_folder = cwd.empty() ? "" : "cd '" + cwd + "' && ";
  const std::string command = in_folder + program + " " + args + " >" + out + " 2>" + err + " </dev/null";
  const int status = std::system(command.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::string e;
  readWholeFile(out, r.out, e);
  readWholeFile(err, r.err, e);
  return r;
}

#ifdef IMAGEPRO_CLI
inline CliRun cli(const std::string& args) { return runProgram(IMAGEPRO_CLI, args); }
#endif
#ifdef IMAGEPRO_STUDIES
inline CliRun studies(const std::string& args) { return runProgram(IMAGEPRO_STUDIES, args); }
#endif

inline void writeText(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The file's content, empty when it cannot be read.
inline std::string readText(const std::filesystem::path& path) {
  std::string text, error;
  readWholeFile(path.string(), text, error);
  return text;
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The command names an overview (--help) lists under "Commands:", up to its blank line.
inline std::vector<std::string> overviewCommands(const std::string& overview) {
  std::vector<std::string> names;
  bool listing = false;
  for (const std::string& line : lines(overview)) {
    if (line == "Commands:") {
      listing = true;
    } else if (listing && line.empty()) {
      break;
    } else if (listing) {
      names.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
  }
  return names;
}

}  // namespace imagepro::test
