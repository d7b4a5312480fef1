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
  // The window's sum from column sums slid down the image and, along each row, a prefix
  // sum of them (window = two prefix entries), with replicated borders: a frame's edge is
  // not darker than what lies beyond it. No library filter: those allocate their buffers
  // on every call. The loops over columns have no branches, so they run in vector lanes.
  const auto clampRow = [rows](int y) { return std::clamp(y, 0, rows - 1); };
  std::vector<std::uint32_t>& columns = ws.column_sums;
  std::vector<std::uint32_t>& prefix = ws.row_prefix;
  columns.assign(static_cast<std::size_t>(cols), 0);
  // The prefix runs over the row with `half` replicated columns either side.
  prefix.resize(static_cast<std::size_t>(cols + 2 * half + 1));
  for (int k = -half; k <= half; ++k) {
    const std::uint8_t* g = grey.ptr<std::uint8_t>(clampRow(k));
    for (int x = 0; x < cols; ++x) columns[static_cast<std::size_t>(x)] += g[x];
  }
  const int side = 2 * half + 1;
  const float inverseArea = 1.0f / (static_cast<float>(side) * static_cast<float>(side));
  const float offset = static_cast<float>(std::clamp(options.offset, 0.0, 1.0));
  const float contrast = static_cast<float>(std::clamp(options.min_contrast, 0, 255));

  for (int y = 0; y < rows; ++y) {
    if (y > 0) {  // slide the column sums down by one row
      const std::uint8_t* in = grey.ptr<std::uint8_t>(clampRow(y + half));
      const std::uint8_t* out = grey.ptr<std::uint8_t>(clampRow(y - half - 1));
      std::uint32_t* c = columns.data();
      for (int x = 0; x < cols; ++x) c[x] += static_cast<std::uint32_t>(in[x]) - out[x];
    }
    // prefix[i] = sum of the padded row's first i column sums; padded column j is column
    // clamp(j - half).
    std::uint32_t* p = prefix.data();
    const std::uint32_t* c = columns.data();
    std::uint32_t running = 0;
    p[0] = 0;
    int j = 0;
    for (; j < half; ++j) p[j + 1] = running += c[0];
    for (; j < half + cols; ++j) p[j + 1] = running += c[j - half];
    for (; j < cols + 2 * half; ++j) p[j + 1] = running += c[cols - 1];
    const std::uint8_t* g = grey.ptr<std::uint8_t>(y);
    std::uint8_t* b = binary.ptr<std::uint8_t>(y);
    for (int x = 0; x < cols; ++x) {
      // The window about x covers padded columns x .. x + 2 half.
      // Signed for the vector conversion to float: sums stay below 2^31 for windows up to
      // the settings' 2047 px.
      const float mean = static_cast<float>(static_cast<std::int32_t>(p[x + side] - p[x])) * inverseArea;
      const float drop = std::max(offset * mean, contrast);
      b[x] = static_cast<float>(g[x]) + drop < mean ? 0 : 255;
    }
  }
}

}  // namespace imagepro
