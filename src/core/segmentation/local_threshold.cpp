#include "core/segmentation/local_threshold.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  const int rows = grey.rows, cols = grey.cols;
  const int half = localWindowPx(options, grey.size()) / 2;
  reuseBuffer(binary, grey.size(), allocationSize(grey));
  // The window's mean by running sums, first down the columns, then along the row, with
  // replicated borders (a frame's edge is not darker than what lies beyond it). No
  // library filter: those allocate their buffers on every call.
  const auto clampRow = [rows](int y) { return std::clamp(y, 0, rows - 1); };
  const auto clampCol = [cols](int x) { return std::clamp(x, 0, cols - 1); };
  std::vector<std::uint32_t>& columns = ws.column_sums;
  columns.assign(static_cast<std::size_t>(cols), 0);
  for (int k = -half; k <= half; ++k) {
    const std::uint8_t* g = grey.ptr<std::uint8_t>(clampRow(k));
    for (int x = 0; x < cols; ++x) columns[static_cast<std::size_t>(x)] += g[x];
  }
  const std::uint64_t side = static_cast<std::uint64_t>(2 * half + 1);
  const std::uint64_t area = side * side;
  // mean = sum / area as a multiplication: (sum * inverse) >> 32, exact to below 1/2 grey level.
  const std::uint64_t inverse = ((std::uint64_t{1} << 32) + area / 2) / area;
  const auto relative = static_cast<std::uint32_t>(std::lround(std::clamp(options.offset, 0.0, 1.0) * 256.0));
  const auto absolute = static_cast<std::uint32_t>(std::clamp(options.min_contrast, 0, 255));

  for (int y = 0; y < rows; ++y) {
    if (y > 0) {  // slide the column sums down by one row
      const std::uint8_t* in = grey.ptr<std::uint8_t>(clampRow(y + half));
      const std::uint8_t* out = grey.ptr<std::uint8_t>(clampRow(y - half - 1));
      for (int x = 0; x < cols; ++x) columns[static_cast<std::size_t>(x)] += in[x] - out[x];
    }
    const std::uint8_t* g = grey.ptr<std::uint8_t>(y);
    std::uint8_t* b = binary.ptr<std::uint8_t>(y);
    std::uint64_t sum = 0;
    for (int k = -half; k <= half; ++k) sum += columns[static_cast<std::size_t>(clampCol(k))];
    for (int x = 0; x < cols; ++x) {
      if (x > 0) sum += columns[static_cast<std::size_t>(clampCol(x + half))] -
                        static_cast<std::uint64_t>(columns[static_cast<std::size_t>(clampCol(x - half - 1))]);
      const auto mean = static_cast<std::uint32_t>((sum * inverse + (std::uint64_t{1} << 31)) >> 32);
      const std::uint32_t drop = std::max((mean * relative) >> 8, absolute);
      // Black when grey + drop < mean, written without a subtraction that could wrap.
      b[x] = g[x] + drop < mean ? 0 : 255;
    }
  }
}

}  // namespace imagepro
