#pragma once
// Output buffers that keep their allocation from frame to frame. cv::Mat::create
// reallocates whenever the size changes, and a tracked region changes size every
// frame; here a buffer is allocated once with room for the largest size expected
// and later sizes are views (cv::Mat ROIs) into that allocation. Such a view is not
// continuous in general: index it by rows (ptr(row)), as OpenCV code does.
#include <opencv2/core.hpp>

namespace imagepro {

// Makes `buffer` a CV_8UC1 image of `size`, reusing its allocation when that can hold
// `size` (top-left block of it), otherwise allocating `capacity` (>= size) and viewing
// its top-left block. Pixel values are not preserved.
void reuseBuffer(cv::Mat& buffer, cv::Size size, cv::Size capacity);

// The size of the allocation `image` is a view into (its own size if it is not a view).
cv::Size allocationSize(const cv::Mat& image);

}  // namespace imagepro
