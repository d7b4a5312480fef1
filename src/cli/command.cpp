#include "cli/command.h"

#include <algorithm>
#include <charconv>
#include <cstdio>

namespace imagepro::cli {

namespace {
std::map<std::string, Command>& registry() {
  static std::map<std::string, Command> r;
  return r;
}
}  // namespace

CommandRegistration::CommandRegistration(Command command) {
  auto name = command.name;
  registry().emplace(std::move(name), std::move(command));
}

const std::map<std::string, Command>& commands() { return registry(); }

Args::Args(int argc, char** argv, std::vector<std::string> flags) {
  for (int i = 0; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) == 0 && a.size() > 2) {
      std::string key = a.substr(2);
      const auto eq = key.find('=');
      if (eq != std::string::npos) {
        options_[key.substr(0, eq)] = key.substr(eq + 1);
      } else if (std::find(flags.begin(), flags.end(), key) != flags.end() || key == "help") {
        options_[key] = "";
      } else {
        if (i + 1 >= argc) throw UsageError("--" + key + " needs a value");
        options_[key] = argv[++i];
      }
    } else if (a == "-h") {
      options_["help"] = "";
    } else {
      positionals_.push_back(std::move(a));
    }
  }
}

bool Args::has(const std::string& key) const { return options_.count(key) != 0; }

std::optional<std::string> Args::value(const std::string& key) const {
  const auto it = options_.find(key);
  if (it == options_.end()) return std::nullopt;
  return it->second;
}

std::string Args::valueOr(const std::string& key, const std::string& fallback) const {
  return value(key).value_or(fallback);
}

double Args::number(const std::string& key, double fallback) const {
  const auto v = value(key);
  if (!v) return fallback;
  double out = 0;
  const auto* end = v->data() + v->size();
  const auto [ptr, ec] = std::from_chars(v->data(), end, out);
  if (ec != std::errc() || ptr != end) throw UsageError("--" + key + ": \"" + *v + "\" is not a number");
  return out;
}

int Args::integer(const std::string& key, int fallback) const {
  const auto v = value(key);
  if (!v) return fallback;
  int out = 0;
  const auto* end = v->data() + v->size();
  const auto [ptr, ec] = std::from_chars(v->data(), end, out);
  if (ec != std::errc() || ptr != end) throw UsageError("--" + key + ": \"" + *v + "\" is not a whole number");
  return out;
}

void Args::rejectUnknown(const std::vector<std::string>& known) const {
  for (const auto& [key, unused] : options_) {
    if (key == "help" || key == "config") continue;
    if (std::find(known.begin(), known.end(), key) == known.end())
      throw UsageError("unknown option --" + key);
  }
}

std::filesystem::path outputFolder(const std::string& option, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) throw InputError("--" + option + ": cannot create folder \"" + dir + "\"");
  return dir;
}

Settings loadConfig(const Args& args) {
  Settings settings;
  if (const auto path = args.value("config")) {
    std::string error;
    std::vector<std::string> warnings;
    if (!ok(loadSettings(*path, settings, error, &warnings))) throw InputError(error);
    for (const std::string& w : warnings) std::fprintf(stderr, "imagepro-cli: warning: %s\n", w.c_str());
  }
  return settings;
}

}  // namespace imagepro::cli
