#include "core/analysis/pose_series.h"

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace imagepro {

namespace {

bool parseNumber(const std::string& text, double& value) {
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && std::isfinite(value);
}

}  // namespace

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

Status readPoseSeries(const std::string& path, double frame_rate_hz, std::vector<PoseSample>& out,
                      std::string& error) {
  out.clear();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    error = path + ": no such file";
    return Status::FileNotFound;
  }
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) {
    error = path + ": cannot be read or is empty";
    return Status::FileUnreadable;
  }
  const std::vector<std::string> header = splitCsvLine(line);
  auto column = [&](const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  };
  const std::array<const char*, 6> pose_names{"Rx_deg", "Ry_deg", "Rz_deg", "Tx_mm", "Ty_mm", "Tz_mm"};
  std::array<int, 6> pose_columns{};
  for (std::size_t k = 0; k < pose_names.size(); ++k) {
    pose_columns[k] = column(pose_names[k]);
    if (pose_columns[k] < 0) {
      error = path + ": line 1: no " + pose_names[k] + " column (not a pose CSV)";
      return Status::FileUnreadable;
    }
  }
  const int frame_column = column("frame");
  const int status_column = column("status");
  const int time_column = column("timestamp_s");
  if (status_column < 0) {
    error = path + ": line 1: no status column (not a pose CSV)";
    return Status::FileUnreadable;
  }

  std::vector<double> stamps, frames;
  bool numeric_frames = frame_column >= 0;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> f = splitCsvLine(line);
    auto field = [&](int c) -> const std::string& {
      static const std::string kEmpty;
      return c >= 0 && static_cast<std::size_t>(c) < f.size() ? f[static_cast<std::size_t>(c)] : kEmpty;
    };
    auto bad = [&](const std::string& what) {
      error = path + ": line " + std::to_string(line_number) + ": " + what;
      out.clear();
      return Status::FileUnreadable;
    };
    PoseSample s;
    s.valid = field(status_column) == "ok";
    if (s.valid) {
      std::array<double, 6> v{};
      for (std::size_t k = 0; k < 6; ++k)
        if (!parseNumber(field(pose_columns[k]), v[k])) return bad(std::string("bad ") + pose_names[k] + " value");
      s.pose = Pose{v[0], v[1], v[2], v[3], v[4], v[5]};
    }
    double stamp = 0.0;
    if (time_column >= 0 && !parseNumber(field(time_column), stamp)) return bad("bad timestamp_s value");
    stamps.push_back(stamp);
    double frame = 0.0;
    if (numeric_frames && !parseNumber(field(frame_column), frame)) numeric_frames = false;
    frames.push_back(frame);
    out.push_back(s);
  }

  bool increasing = time_column >= 0 && !stamps.empty();
  for (std::size_t i = 1; increasing && i < stamps.size(); ++i) increasing = stamps[i] > stamps[i - 1];
  if (increasing) {
    for (std::size_t i = 0; i < out.size(); ++i) out[i].t_s = stamps[i];
    return Status::Ok;
  }
  if (!(frame_rate_hz > 0.0)) {
    error = path + ": no increasing timestamp_s column: give the frame rate";
    out.clear();
    return Status::InvalidSettings;
  }
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i].t_s = (numeric_frames ? frames[i] : static_cast<double>(i)) / frame_rate_hz;
  return Status::Ok;
}

}  // namespace imagepro
