#include "core/pipeline/data_out.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/common/pose_csv.h"

namespace imagepro {

namespace {

std::string regionColumns(const cv::Rect& r) {
  if (r.empty()) return ",,,";
  return std::to_string(r.x) + ',' + std::to_string(r.y) + ',' + std::to_string(r.width) + ',' +
         std::to_string(r.height);
}

std::string numberedName(const std::filesystem::path& p, int k) {
  return (p.parent_path() / (p.stem().string() + "-" + std::to_string(k) + p.extension().string())).string();
}

}  // namespace

DataOut::~DataOut() { close(); }

std::string DataOut::header() {
  std::string extra = "timestamp_s,search_x,search_y,search_w,search_h,target_x,target_y,target_w,target_h";
  for (std::size_t s = 0; s < kStageCount; ++s) {
    extra += ',';
    extra += stageName(static_cast<Stage>(s));
    extra += "_us";
  }
  return poseCsvHeader(extra);
}

std::string DataOut::row(const FrameResult& r) {
  char ts[32];
  std::snprintf(ts, sizeof ts, "%.6f", r.timestamp_s);
  std::string extra = ts;
  extra += ',' + regionColumns(r.search_region) + ',' + regionColumns(r.detected_region);
  for (double us : r.times.us) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ",%.1f", us);
    extra += buf;
  }
  const std::string frame = r.name.empty() ? std::to_string(r.index) : r.name;
  return poseCsvRow(frame, r.status, r.pose, extra);
}

Status DataOut::open(const std::string& path, ExistingFile existing, std::string& error) {
  close();
  namespace fs = std::filesystem;
  std::error_code ec;
  std::string target = path;
  bool append = false;
  if (fs::exists(target, ec)) {
    switch (existing) {
      case ExistingFile::Fail:
        error = path + ": file exists (choose append or a new name)";
        return Status::FileNotWritable;
      case ExistingFile::Append:
        append = true;
        break;
      case ExistingFile::NewName:
        for (int k = 1; fs::exists(target, ec); ++k) target = numberedName(path, k);
        break;
    }
  }
  const bool empty = !append || fs::file_size(target, ec) == 0;
  // "a" never truncates; "wx" refuses to replace a file that appeared meanwhile.
  file_ = std::fopen(target.c_str(), append ? "a" : "wx");
  if (!file_) {
    error = target + ": cannot open for writing: " + std::strerror(errno);
    return Status::FileNotWritable;
  }
  path_ = target;
  if (empty) {
    const std::string h = header() + "\n";
    if (std::fputs(h.c_str(), file_) < 0 || std::fflush(file_) != 0) {
      error = target + ": cannot write: " + std::strerror(errno);
      close();
      return Status::FileNotWritable;
    }
  }
  return Status::Ok;
}

bool DataOut::write(const FrameResult& result, std::string& error) {
  if (!file_) {
    error = "data out is not open";
    return false;
  }
  const std::string line = row(result) + "\n";
  if (std::fputs(line.c_str(), file_) < 0 || std::fflush(file_) != 0) {
    error = path_ + ": cannot write: " + std::strerror(errno);
    close();
    return false;
  }
  return true;
}

void DataOut::close() {
  if (file_) std::fclose(file_);
  file_ = nullptr;
}

}  // namespace imagepro
