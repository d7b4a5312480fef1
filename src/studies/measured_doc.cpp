#include "studies/measured_doc.h"

#include <cctype>
#include <set>

#include "core/common/atomic_file.h"

namespace imagepro::studies {
namespace {

constexpr std::string_view kOpen = "<!--m:", kOpenEnd = "-->", kClose = "<!--/m-->";

bool validName(std::string_view name) {
  if (name.empty()) return false;
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-')) return false;
  return true;
}

int lineOf(const std::string& doc, std::size_t at) {
  int line = 1;
  for (std::size_t i = 0; i < at && i < doc.size(); ++i) line += doc[i] == '\n' ? 1 : 0;
  return line;
}

// A block's value between blank lines, whatever blank lines the value itself starts or ends with.
std::string blockText(std::string value) {
  value.erase(0, value.find_first_not_of('\n'));
  while (!value.empty() && value.back() == '\n') value.pop_back();
  return value.empty() ? "\n" : "\n\n" + value + "\n\n";
}

}  // namespace

bool fillMeasuredPlaces(std::string& doc, const MeasuredValues& values,
                        const std::vector<std::string>& required_prefixes, std::string& error) {
  std::string out;
  out.reserve(doc.size());
  std::set<std::string> placed;
  std::size_t at = 0;
  for (std::size_t open; (open = doc.find(kOpen, at)) != std::string::npos;) {
    const std::size_t nameStart = open + kOpen.size();
    const std::size_t nameEnd = doc.find(kOpenEnd, nameStart);
    const std::string name = nameEnd == std::string::npos ? "" : doc.substr(nameStart, nameEnd - nameStart);
    if (!validName(name)) {
      error = "line " + std::to_string(lineOf(doc, open)) + ": a measured place without a valid name";
      return false;
    }
    const std::size_t textStart = nameEnd + kOpenEnd.size();
    const std::size_t close = doc.find(kClose, textStart);
    const std::size_t nextOpen = doc.find(kOpen, textStart);
    if (close == std::string::npos || (nextOpen != std::string::npos && nextOpen < close)) {
      error = "line " + std::to_string(lineOf(doc, open)) + ": the measured place '" + name + "' has no " +
              std::string(kClose);
      return false;
    }
    const bool block = textStart < doc.size() && doc[textStart] == '\n';
    if (!block && doc.find('\n', textStart) < close) {
      error = "line " + std::to_string(lineOf(doc, open)) + ": the inline measured place '" + name +
              "' runs over a line end (a block's opening marker ends its line)";
      return false;
    }
    // Markdown reads a line that begins with "<!--" as raw HTML, so an inline place there
    // would show its line unformatted (and interrupt the paragraph it is in).
    if (!block && (open == 0 || doc[open - 1] == '\n')) {
      error = "line " + std::to_string(lineOf(doc, open)) + ": the inline measured place '" + name +
              "' begins its line, which Markdown would show as raw HTML: start the line with a word";
      return false;
    }
    out.append(doc, at, textStart - at);
    const auto value = values.find(name);
    if (value == values.end()) {
      for (const std::string& prefix : required_prefixes)
        if (name.rfind(prefix, 0) == 0) {
          error = "line " + std::to_string(lineOf(doc, open)) + ": the study measured no value for '" + name + "'";
          return false;
        }
      out.append(doc, textStart, close - textStart);
    } else {
      if (!block && value->second.find('\n') != std::string::npos) {
        error = "line " + std::to_string(lineOf(doc, open)) + ": '" + name +
                "' is a table or list, but its place is inline";
        return false;
      }
      out += block ? blockText(value->second) : value->second;
      placed.insert(name);
    }
    out += kClose;
    at = close + kClose.size();
  }
  out.append(doc, at, std::string::npos);
  for (const auto& [name, text] : values)
    if (!placed.count(name)) {
      error = "no place for the measured value '" + name + "' (" + std::string(kOpen) + name + std::string(kOpenEnd) +
              "..." + std::string(kClose) + "): the doc and the study disagree";
      return false;
    }
  doc = std::move(out);
  return true;
}

bool checkMeasuredDoc(const std::string& template_path, std::string& error) {
  std::string doc;
  if (!readWholeFile(template_path, doc, error)) {
    error += " (the study fills the measured places of its hand-written doc; give it with --template)";
    return false;
  }
  if (!fillMeasuredPlaces(doc, {}, {}, error)) {
    error = template_path + ": " + error;
    return false;
  }
  return true;
}

bool fillMeasuredDoc(const std::string& template_path, const std::string& out_path, const MeasuredValues& values,
                     const std::vector<std::string>& required_prefixes, std::string& error) {
  std::string doc;
  if (!readWholeFile(template_path, doc, error)) {
    error += " (the study fills the measured places of its hand-written doc; give it with --template)";
    return false;
  }
  if (!fillMeasuredPlaces(doc, values, required_prefixes, error)) {
    error = template_path + ": " + error;
    return false;
  }
  return writeFileAtomically(out_path, doc, error);
}

}  // namespace imagepro::studies
