#pragma once
// Video files as a frame source (thesis 2.2 lists files and a frame grabber; a
// recorded video is the grabber's frames kept for later): AVI, MP4, MKV, MOV ...
// whatever OpenCV's video reader (FFmpeg) decodes, delivered as 8-bit grey with the
// frame's index and its time in the file. Paced at the file's frame rate, or read as
// fast as possible.
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

#include <cstdint>
#include <string>

#include "core/source/source.h"

namespace imagepro {

enum class VideoPacing : std::uint8_t {
  FileRate,         // frameRateHz() is the file's rate: the frame loop waits between frames
  AsFastAsPossible  // frameRateHz() is 0: every frame as soon as the last is done
};

// True for the usual video file extensions (case-insensitive).
bool isVideoFileName(const std::string& path);

class VideoFileSource final : public FrameSource {
 public:
  explicit VideoFileSource(std::string path, VideoPacing pacing = VideoPacing::FileRate);

  // Opens the file (next() does it when not yet done). FileNotFound, or
  // FileUnreadable when no reader can decode it; lastError() names the file.
  Status open();
  // Back to the first frame.
  Status restart();

  // Frame::index is the frame's position in the file from 0; Frame::timestamp_s its
  // presentation time (index / rate when the file gives none). The image is reused:
  // valid until the next call. EndOfStream after the last frame.
  Status next(Frame& out) override;
  std::string lastError() const override { return error_; }
  double frameRateHz() const override { return pacing_ == VideoPacing::FileRate ? file_rate_hz_ : 0.0; }
  // "video clip.avi 25 Hz, frame 12 of 250".
  std::string describe() const override;

  double fileRateHz() const { return file_rate_hz_; }
  // As the container states it; 0 when unknown.
  std::int64_t frameCount() const { return frame_count_; }

 private:
  std::string path_;
  VideoPacing pacing_;
  cv::VideoCapture capture_;
  bool opened_ = false;
  double file_rate_hz_ = 0.0;
  std::int64_t frame_count_ = 0;
  std::int64_t next_index_ = 0;
  cv::Mat decoded_;
  cv::Mat grey_;
  std::string error_;
};

}  // namespace imagepro
