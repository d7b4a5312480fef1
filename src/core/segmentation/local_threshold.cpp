#include "core/segmentation/local_threshold.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

#include "core/segmentation/image_buffer.h"

namespace imagepro {

int localWindowPx(const BinarizationOptions& options, cv::Size size) {
  const int side = options.window_px > 0 ? options.window_px : std::max(15, size.width / 16);
  return side | 1;
}

void binarizeLocal(const cv::Mat& grey, const BinarizationOptions& options, LocalThresholdWorkspace& ws,
                   cv::Mat& binary) {
  if (grey.empty() || grey.type() != CV_8UC1) {
    binary = cv::Mat();
    return;
  }
  const int side = localWindowPx(options, grey.size());
  reuseBuffer(ws.mean, grey.size(), allocationSize(grey));
  reuseBuffer(binary, grey.size(), allocationSize(grey));
  // Replicated borders: a frame's edge is not darker than what lies beyond it.
  cv::blur(grey, ws.mean, cv::Size(side, side), cv::Point(-1, -1), cv::BORDER_REPLICATE);

  // offset * m in 8.8 fixed point, so the row loop stays in 16-bit lanes.
  const auto relative = static_cast<std::uint16_t>(std::lround(std::clamp(options.offset, 0.0, 1.0) * 256.0));
  const auto absolute = static_cast<std::uint16_t>(std::clamp(options.min_contrast, 0, 255));
  for (int y = 0; y < grey.rows; ++y) {
    const std::uint8_t* g = grey.ptr<std::uint8_t>(y);
    const std::uint8_t* m = ws.mean.ptr<std::uint8_t>(y);
    std::uint8_t* b = binary.ptr<std::uint8_t>(y);
    for (int x = 0; x < grey.cols; ++x) {
      const std::uint16_t mean = m[x];
      const std::uint16_t drop = std::max<std::uint16_t>(static_cast<std::uint16_t>((mean * relative) >> 8), absolute);
      // Black when g + drop < mean, written without a subtraction that could wrap.
      b[x] = static_cast<std::uint16_t>(g[x] + drop) < mean ? 0 : 255;
    }
  }
}

}  // namespace imagepro
