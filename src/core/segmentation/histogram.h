#pragma once
// Grey-level histogram h(g) of thesis 2.3. The engine counts the tracked region
// (thesis 5.2.2) as a view into the frame, without copying it.
#include <opencv2/core.hpp>

#include <array>
#include <cstdint>

namespace imagepro {

using Histogram = std::array<std::uint32_t, 256>;

// Histogram of a CV_8UC1 image, which may be a region view into a larger one
// (grey(roi)); all zeros for an empty or non-CV_8UC1 image. The rows of a view are
// fetched a few rows ahead of the count, as their cache lines are not consecutive.
void computeHistogram(const cv::Mat& grey, Histogram& hist);

// The histogram of `grey` (as above) estimated from every rowStep-th row, from the first:
// each of their counts times rowStep (1 or less: every row, the exact histogram). Every row
// is still fetched ahead into the cache, for what reads the image next.
void estimateHistogramFromRows(const cv::Mat& grey, int rowStep, Histogram& hist);

}  // namespace imagepro
