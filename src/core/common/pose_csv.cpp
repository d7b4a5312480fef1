#include "core/common/pose_csv.h"

#include <cstdio>

namespace imagepro {

std::string poseCsvHeader(std::string_view extra_columns) {
  std::string h = "frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm";
  if (!extra_columns.empty()) {
    h += ',';
    h += extra_columns;
  }
  return h;
}

std::string csvField(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

std::string poseCsvRow(std::string_view frame, Status status, const std::optional<Pose>& pose,
                       std::string_view extra) {
  std::string row = csvField(frame);
  row += ',';
  row += statusName(status);
  if (ok(status) && pose) {
    char buf[160];
    std::snprintf(buf, sizeof buf, ",%.6f,%.6f,%.6f,%.6f,%.6f,%.6f", pose->rx_deg, pose->ry_deg, pose->rz_deg,
                  pose->tx_mm, pose->ty_mm, pose->tz_mm);
    row += buf;
  } else {
    row += ",,,,,,";
  }
  if (!extra.empty()) {
    row += ',';
    row += extra;
  }
  return row;
}

}  // namespace imagepro
