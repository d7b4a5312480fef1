// Runs imagepro-cli as a user would, for the CLI tests: the exit code and what it
// printed on each stream.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
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

// Runs the CLI with `args`, capturing stdout and stderr through files.
inline CliRun cli(const std::string& args) {
  namespace fs = std::filesystem;
  // ctest runs the tests in parallel processes: each captures into files of its own.
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / ("cli_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string out = (dir / "stdout.txt").string(), err = (dir / "stderr.txt").string();
  const std::string command = std::string(IMAGEPRO_CLI) + " " + args + " >" + out + " 2>" + err + " </dev/null";
  const int status = std::system(command.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::string e;
  readWholeFile(out, r.out, e);
  readWholeFile(err, r.err, e);
  return r;
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

}  // namespace imagepro::test
