#pragma once
// Grey-level histogram h(g) of thesis 2.3, built in the same pass that crops the
// frame to the tracked region (thesis 5.2.2), so the threshold costs no extra pass.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

namespace imagepro {

using Histogram = std::array<std::uint32_t, 256>;

// Histogram of the whole CV_8UC1 image (all zeros for an empty or non-CV_8UC1 image).
void computeHistogram(const cv::Mat& grey, Histogram& hist);
// Copies grey(roi) into `crop` (reusing its buffer) and builds its histogram in the same pass.
// The roi is clipped to the image; an empty result gives an empty crop and a zero histogram.
// `crop` may be a view into a larger reused allocation (see image_buffer.h): index it by row.
void cropWithHistogram(const cv::Mat& grey, cv::Rect roi, cv::Mat& crop, Histogram& hist);

}  // namespace imagepro
