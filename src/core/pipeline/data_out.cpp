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

enum class Ending : std::uint8_t { Whole, CutRow, CutHeader };

// How an existing data-out file ends: on a line end, or inside a row (or inside the
// header, when not even its first line is whole) that a killed write left behind.
Ending howItEnds(std::FILE* f) {
  if (std::fseek(f, -1, SEEK_END) != 0 || std::fgetc(f) == '\n') return Ending::Whole;
  std::rewind(f);
  for (int c; (c = std::fgetc(f)) != EOF;)
    if (c == '\n') return Ending::CutRow;
  return Ending::CutHeader;
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
  return poseCsvHeader(extra + ",rim_seen");
}

std::string DataOut::row(const FrameResult& r) {
  std::string extra = poseNumber(r.timestamp_s);
  extra += ',' + regionColumns(r.search_region) + ',' + regionColumns(r.detected_region);
  for (double us : r.times.us) {
    char buf[32];
    std::snprintf(buf, sizeof buf, ",%.1f", us);
    extra += buf;
  }
  extra += ',' + rimSeenCell(r);
  return poseCsvRow(frameLabel(r), r.status, r.pose, extra);
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
  lost_rows_ = 0;
  notice_.clear();
  bool empty = !append || fs::file_size(target, ec) == 0;
  // "a" never truncates (every write goes to the end, reads may go anywhere); "wx"
  // refuses to replace a file that appeared meanwhile.
  file_ = std::fopen(target.c_str(), append ? "a+" : "wx");
  if (!file_) {
    error = target + ": cannot open for writing: " + std::strerror(errno);
    return Status::FileNotWritable;
  }
  path_ = target;
  std::string start;  // what goes before the first row
  if (!empty) {
    switch (howItEnds(file_)) {
      case Ending::Whole: break;
      case Ending::CutRow:
        start = "\n";
        lost_rows_ = 1;
        notice_ = target + ": its last row was cut off (an earlier run stopped while writing it); that row is "
                           "lost, new rows start on a line of their own";
        break;
      case Ending::CutHeader:
        start = "\n";
        empty = true;  // the header again, whole
        notice_ = target + ": its header was cut off (an earlier run stopped while writing it); the header is "
                           "written again on a line of its own";
        break;
    }
    std::fseek(file_, 0, SEEK_END);  // an update stream needs a seek between reading and writing
  }
  if (empty) start += header() + "\n";
  if (!start.empty()) {
    if (std::fputs(start.c_str(), file_) < 0 || std::fflush(file_) != 0) {
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
