#pragma once
// The reduced image a full-frame search looks at first (stage_chain.h): each pixel the mean
// of a factor x factor block of the input. A target whose rim is tens of pixels across keeps
// its disk, card and rim at a factor's fraction of the pixels, and every stage after the
// threshold costs about the square of the factor less.
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

namespace imagepro {

// The largest factor reduceByBlockMean takes: a block's sum then fits 16 bits.
inline constexpr int kMaxReduceFactor = 15;

// The side of the reduced image a search region of `width` pixels is brought down to, and
// the factor that gets there: width / kCoarseWidthPx (whole), at most kMaxReduceFactor; below
// 2 no reduction pays (1). At 640 x 480 the factor is 2, at 1920 x 1080 it is 6, so the
// target has about the same size in pixels in every reduced image.
inline constexpr int kCoarseWidthPx = 320;
int coarseFactor(int width);

// `out` = grey reduced by `factor`: out(y, x) is the mean of grey's block of rows
// [y * factor, (y + 1) * factor) and columns alike, rounded to the nearest level; rows
// and columns past the last whole block are left out. CV_8UC1 of
// (grey.cols / factor) x (grey.rows / factor), keeping its allocation from call to call
// (image_buffer.h; allocated at the size of the image grey is a view into). Empty when grey is empty or not CV_8UC1, when factor is outside
// [1, kMaxReduceFactor], or when the result would have no pixel. `rowSums` is a buffer
// reused from call to call.
void reduceByBlockMean(const cv::Mat& grey, int factor, cv::Mat& out, std::vector<std::uint16_t>& rowSums);

}  // namespace imagepro
