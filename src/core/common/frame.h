#pragma once
// A frame travelling through the pipeline: an 8-bit grey image (CV_8UC1) with its
// index, time and, for virtual frames, the exact pose it was rendered at.
#include <opencv2/core.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "core/common/geometry.h"

namespace imagepro {

struct Frame {
  cv::Mat image;                   // CV_8UC1
  std::int64_t index = 0;          // 0-based position in the stream
  double timestamp_s = 0.0;        // capture (or render) time, seconds
  std::string name;                // file name for file input, empty otherwise
  std::optional<Pose> truth;       // ground truth for virtual frames
};

}  // namespace imagepro
