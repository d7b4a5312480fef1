#pragma once
// Grey-level histogram h(g) of thesis 2.3, built in the same pass that crops the
// frame to the tracked region (thesis 5.2.2), so the threshold costs no extra pass.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

namespace imagepro {

using Histogram = std::array<std::uint32_t, 256>;

// Histogram of the whole CV_8UC1 image.
void computeHistogram(const cv::Mat& grey, Histogram& hist);
// Copies grey(roi) into `crop` (reusing its buffer) and builds its histogram in the same pass.
// The roi is clipped to the image.
void cropWithHistogram(const cv::Mat& grey, cv::Rect roi, cv::Mat& crop, Histogram& hist);

}  // namespace imagepro
