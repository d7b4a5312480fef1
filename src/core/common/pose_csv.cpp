#include "core/common/pose_csv.h"

#include <cstdio>

namespace imagepro {

std::array<double, 6> poseColumnValues(const Pose& p) {
  return {p.rx_deg, p.ry_deg, p.rz_deg, p.tx_mm, p.ty_mm, p.tz_mm};
}

std::string poseNumber(double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", value);
  return buf;
}

std::string poseCsvHeader(std::string_view extra_columns) {
  std::string h = "frame,status";
  for (std::string_view name : kPoseColumnNames) {
    h += ',';
    h += name;
  }
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
    for (double v : poseColumnValues(*pose)) row += ',' + poseNumber(v);
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
