#pragma once
// The subcommands of imagepro-cli and imagepro-studies. Each lives in its own
// cmd_<name>.cpp and registers itself with a static CommandRegistration, so adding a
// command touches one file; both programs' main() is runCommands.
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/settings/settings.h"

namespace imagepro::cli {

// Parsed command line of one subcommand: --key value, --flag, and positionals.
class Args {
 public:
  // `flags` are the options that take no value; every other --option takes one.
  Args(int argc, char** argv, std::vector<std::string> flags);

  bool has(const std::string& key) const;
  std::optional<std::string> value(const std::string& key) const;
  std::string valueOr(const std::string& key, const std::string& fallback) const;
  // Numeric option; throws UsageError naming the option when it is not a number.
  double number(const std::string& key, double fallback) const;
  int integer(const std::string& key, int fallback) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  // Options given but not in `known`: each is a usage error.
  void rejectUnknown(const std::vector<std::string>& known) const;

 private:
  std::map<std::string, std::string> options_;
  std::vector<std::string> positionals_;
};

// A problem with the command line: printed as one line, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// A problem with the input (missing file, malformed settings): one line, exit code 1.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Loads --config FILE over the defaults (or returns the defaults); throws InputError.
Settings loadConfig(const Args& args);

// The folder an option names for the files a command writes, created with its parents
// when missing; InputError "--OPTION: cannot create folder ..." when it cannot be.
std::filesystem::path outputFolder(const std::string& option, const std::string& dir);

struct Command {
  std::string name;
  std::string summary;  // one line for the command list
  std::string usage;    // full --help text
  std::vector<std::string> flags;  // options without a value
  std::function<int(const Args&)> run;
};

struct CommandRegistration {
  explicit CommandRegistration(Command command);
};

const std::map<std::string, Command>& commands();

// The whole main() of a program made of registered commands: the overview (`summary`
// is its first line), each command's --help, and every error as one line prefixed
// with `program` (usage: exit 2; input and anything else: exit 1).
int runCommands(const char* program, const char* summary, int argc, char** argv);

}  // namespace imagepro::cli
