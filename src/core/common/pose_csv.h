#pragma once
// The machine-readable pose output of docs/conventions.md, one row per frame:
//   frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm[,more columns]
// `frame` is the file name for file input and the index otherwise; the pose
// columns are empty unless the status is ok. Every writer of poses uses this.
#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro {

// The six pose columns, in the order of the header; the live stream's JSON uses the same names.
inline constexpr std::array<std::string_view, 6> kPoseColumnNames{"Rx_deg", "Ry_deg", "Rz_deg",
                                                                  "Tx_mm",  "Ty_mm",  "Tz_mm"};
// A pose's six values in the order of kPoseColumnNames.
std::array<double, 6> poseColumnValues(const Pose& pose);
// A number as every pose writer prints it (six decimals): the pose columns and timestamps.
std::string poseNumber(double value);

// The header line without a newline, followed by `extra_columns` (comma separated) if given.
std::string poseCsvHeader(std::string_view extra_columns = {});
// One row without a newline; `extra` is appended after a comma if non-empty.
std::string poseCsvRow(std::string_view frame, Status status, const std::optional<Pose>& pose,
                       std::string_view extra = {});
// Quotes a field if it holds a comma, quote or newline (file names may).
std::string csvField(std::string_view text);

}  // namespace imagepro
