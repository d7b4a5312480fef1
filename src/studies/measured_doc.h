#pragma once
// A study's report is a hand-written doc with places for the figures it measures; the study
// fills the places and leaves every other line as it is, so the prose lives in docs/*.md.
//
// A place is <!--m:NAME-->TEXT<!--/m-->. Inline, TEXT is one value in a sentence. When the
// opening marker ends its line, the place is a block (a table, a list): its TEXT is the value
// between blank lines, and the closing marker stands on a line of its own. An inline place
// never begins a line (Markdown would show that line as raw HTML). NAME is letters, digits
// and . _ - ; the same NAME may stand in several places.
#include <map>
#include <string>
#include <vector>

namespace imagepro::studies {

using MeasuredValues = std::map<std::string, std::string>;

// Replaces the TEXT of every place whose NAME has a value. Fails with `error` naming the
// problem on: a malformed or unterminated place, a value the doc has no place for (the doc and
// the study disagree), or a place whose NAME starts with one of `required_prefixes` (the parts
// the study ran) but has no value. Places of parts not run keep their TEXT.
bool fillMeasuredPlaces(std::string& doc, const MeasuredValues& values,
                        const std::vector<std::string>& required_prefixes, std::string& error);

// Reads `template_path` and checks that its places are well formed, so that a study fails
// before it measures for minutes rather than after. The error names the file.
bool checkMeasuredDoc(const std::string& template_path, std::string& error);

// Reads `template_path`, fills it and writes `out_path` atomically (the two may be the same
// file). The error names the file.
bool fillMeasuredDoc(const std::string& template_path, const std::string& out_path, const MeasuredValues& values,
                     const std::vector<std::string>& required_prefixes, std::string& error);

}  // namespace imagepro::studies
