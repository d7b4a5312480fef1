#pragma once
// Reads a reconstructed sequence back from the pose CSV of docs/conventions.md (the output
// of `imagepro-cli reconstruct`, or data out with its timestamp_s column), for the
// case studies. Columns are found by their header names, so more columns may follow
// in any order; a row whose status is not "ok" is a frame without a pose.
#include <string>
#include <vector>

#include "core/analysis/pendulum.h"
#include "core/common/status.h"

namespace imagepro {

// Each row's time is its timestamp_s when the file has that column with increasing
// values; otherwise frame / frame_rate_hz for a numeric frame column, or the row number
// / frame_rate_hz (frame_rate_hz <= 0 then gives InvalidSettings). FileNotFound,
// FileUnreadable (with `error` naming the file, the line and the problem: a missing
// column, a malformed number) or Ok.
Status readPoseSeries(const std::string& path, double frame_rate_hz, std::vector<PoseSample>& out,
                      std::string& error);

// Splits one CSV line into fields (double-quoted fields may hold commas and "" quotes).
std::vector<std::string> splitCsvLine(const std::string& line);

}  // namespace imagepro
