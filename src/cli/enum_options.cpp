#include "cli/enum_options.h"

#include <algorithm>

namespace imagepro::cli {

namespace {
constexpr std::size_t kIndent = 6;   // under the option's own line
constexpr std::size_t kWidth = 88;  // about the widest line of the help texts
}  // namespace

std::string choicesHelp(const std::vector<SettingKey::Choice>& rows) {
  std::size_t key_width = 0;
  for (const auto& r : rows) key_width = std::max(key_width, r.key.size());
  const std::size_t text_column = kIndent + key_width + 2;
  std::string out;
  for (const auto& r : rows) {
    std::string line(kIndent, ' ');
    line += r.key;
    line.append(text_column - line.size(), ' ');
    std::size_t used = text_column;
    const std::string text = std::string(r.label) + ": " + std::string(r.description);
    // Word by word; a word that would pass the width starts a new line under the text.
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find(' ', start);
      if (end == std::string::npos) end = text.size();
      const std::size_t word = end - start;
      if (used > text_column && used + 1 + word > kWidth) {
        out += line + "\n";
        line.assign(text_column, ' ');
        used = text_column;
      } else if (used > text_column) {
        line += ' ';
        ++used;
      }
      line.append(text, start, word);
      used += word;
      start = end + 1;
    }
    out += line + "\n";
  }
  return out;
}

}  // namespace imagepro::cli
