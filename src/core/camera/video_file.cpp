#include "core/camera/video_file.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio/registry.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace imagepro {

namespace {

std::string fileName(const std::string& path) { return std::filesystem::path(path).filename().string(); }

}  // namespace

bool isVideoFileName(const std::string& path) {
  static constexpr std::array<const char*, 12> kExtensions{".avi", ".mp4", ".mkv", ".mov", ".webm", ".mpg",
                                                           ".mpeg", ".m4v", ".wmv", ".ogv", ".flv", ".ts"};
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end();
}

VideoFileSource::VideoFileSource(std::string path, VideoPacing pacing) : path_(std::move(path)), pacing_(pacing) {}

Status VideoFileSource::open() {
  opened_ = false;
  next_index_ = 0;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path_, ec)) {
    error_ = path_ + ": no such video file";
    return Status::FileNotFound;
  }
  // FFmpeg where OpenCV has it: the automatic choice would also try a device node, an
  // image-name pattern or GStreamer, each complaining on stderr about a file it cannot read.
  const int backend = cv::videoio_registry::hasBackend(cv::CAP_FFMPEG) ? cv::CAP_FFMPEG : cv::CAP_ANY;
  if (!capture_.open(path_, backend)) {
    error_ = path_ + ": not a video that can be decoded";
    return Status::FileUnreadable;
  }
  file_rate_hz_ = capture_.get(cv::CAP_PROP_FPS);
  if (!std::isfinite(file_rate_hz_) || file_rate_hz_ < 0.0 || file_rate_hz_ > 1e4) file_rate_hz_ = 0.0;
  const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
  frame_count_ = std::isfinite(count) && count > 0.0 ? static_cast<std::int64_t>(count) : 0;
  opened_ = true;
  error_.clear();
  return Status::Ok;
}

Status VideoFileSource::restart() {
  capture_.release();
  return open();
}

Status VideoFileSource::next(Frame& out) {
  out.name.clear();
  out.truth.reset();
  if (!opened_) {
    if (const Status s = open(); !ok(s)) {
      out.image.release();
      return s;
    }
  }
  out.index = next_index_;
  if (!capture_.read(decoded_) || decoded_.empty()) {
    out.image.release();
    error_ = fileName(path_) + ": end of the video after " + std::to_string(next_index_) + " frames";
    return Status::EndOfStream;
  }
  const double ms = capture_.get(cv::CAP_PROP_POS_MSEC);
  const bool stamped = std::isfinite(ms) && (ms > 0.0 || next_index_ == 0);
  out.timestamp_s = stamped ? ms / 1000.0
                            : (file_rate_hz_ > 0.0 ? static_cast<double>(next_index_) / file_rate_hz_ : 0.0);
  ++next_index_;
  if (decoded_.type() == CV_8UC1) {
    out.image = decoded_;
  } else if (decoded_.type() == CV_8UC3) {
    cv::cvtColor(decoded_, grey_, cv::COLOR_BGR2GRAY);
    out.image = grey_;
  } else if (decoded_.type() == CV_8UC4) {
    cv::cvtColor(decoded_, grey_, cv::COLOR_BGRA2GRAY);
    out.image = grey_;
  } else {
    out.image.release();
    error_ = fileName(path_) + ": frame " + std::to_string(out.index) + " has a pixel type other than 8-bit";
    return Status::EmptyFrame;
  }
  return Status::Ok;
}

std::string VideoFileSource::describe() const {
  char rate[32] = "";
  if (file_rate_hz_ > 0.0) std::snprintf(rate, sizeof rate, " %.4g Hz", file_rate_hz_);
  std::string d = "video " + fileName(path_) + rate;
  if (next_index_ > 0) {
    d += ", frame " + std::to_string(next_index_ - 1);
    if (frame_count_ > 0) d += " of " + std::to_string(frame_count_);
  }
  return d;
}

}  // namespace imagepro
