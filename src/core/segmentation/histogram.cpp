#include "core/segmentation/histogram.h"

#include <cstring>

#include "core/segmentation/image_buffer.h"

namespace imagepro {

namespace {

// Four partial histograms, so consecutive pixels of the same grey level do not wait
// on each other's increment (a store-to-load dependency that halves the speed).
struct PartialHistograms {
  std::uint32_t bins[4][256] = {};

  // Counts the n pixels at p and, when kCopy is set, writes them to `copy` in the same
  // pass. Pixels are read four at a time as one word: fewer loads for the same stores.
  template <bool kCopy>
  void addRow(const std::uint8_t* p, int n, std::uint8_t* copy = nullptr) {
    int i = 0;
    for (; i + 8 <= n; i += 8) {
      std::uint32_t w0, w1;
      std::memcpy(&w0, p + i, 4);
      std::memcpy(&w1, p + i + 4, 4);
      if constexpr (kCopy) {
        std::memcpy(copy + i, &w0, 4);
        std::memcpy(copy + i + 4, &w1, 4);
      }
      add4(w0);
      add4(w1);
    }
    for (; i < n; ++i) {
      if constexpr (kCopy) copy[i] = p[i];
      ++bins[0][p[i]];
    }
  }

  // The four bytes of w, each into its own partial histogram (byte order does not matter).
  void add4(std::uint32_t w) {
    ++bins[0][w & 0xFF];
    ++bins[1][(w >> 8) & 0xFF];
    ++bins[2][(w >> 16) & 0xFF];
    ++bins[3][w >> 24];
  }

  void sumInto(Histogram& hist) const {
    for (int g = 0; g < 256; ++g) hist[g] = bins[0][g] + bins[1][g] + bins[2][g] + bins[3][g];
  }
};

bool isGrey(const cv::Mat& image) { return !image.empty() && image.type() == CV_8UC1; }

}  // namespace

void computeHistogram(const cv::Mat& grey, Histogram& hist) {
  hist.fill(0);
  if (!isGrey(grey)) return;
  PartialHistograms partial;
  // A continuous image is one long row.
  const int rows = grey.isContinuous() ? 1 : grey.rows;
  const int cols = grey.isContinuous() ? grey.rows * grey.cols : grey.cols;
  for (int r = 0; r < rows; ++r) partial.addRow<false>(grey.ptr<std::uint8_t>(r), cols);
  partial.sumInto(hist);
}

void cropWithHistogram(const cv::Mat& grey, cv::Rect roi, cv::Mat& crop, Histogram& hist) {
  hist.fill(0);
  if (!isGrey(grey)) {
    crop = cv::Mat();
    return;
  }
  roi &= cv::Rect(0, 0, grey.cols, grey.rows);
  // Writing the crop into the frame's own allocation would overwrite what is still to be read.
  if (!crop.empty() && crop.datastart == grey.datastart) crop = cv::Mat();
  if (roi.empty()) {
    crop = cv::Mat();
    return;
  }
  reuseBuffer(crop, roi.size(), allocationSize(grey));
  PartialHistograms partial;
  for (int r = 0; r < roi.height; ++r)
    partial.addRow<true>(grey.ptr<std::uint8_t>(roi.y + r) + roi.x, roi.width, crop.ptr<std::uint8_t>(r));
  partial.sumInto(hist);
}

}  // namespace imagepro
