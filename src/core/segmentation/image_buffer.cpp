#include "core/segmentation/image_buffer.h"

#include <algorithm>

namespace imagepro {

cv::Size allocationSize(const cv::Mat& image) {
  if (image.empty()) return {0, 0};
  cv::Size whole;
  cv::Point offset;
  image.locateROI(whole, offset);
  return whole;
}

void reuseBuffer(cv::Mat& buffer, cv::Size size, cv::Size capacity) {
  if (!buffer.empty() && buffer.type() == CV_8UC1) {
    if (buffer.size() == size) return;
    cv::Size whole;
    cv::Point offset;
    buffer.locateROI(whole, offset);
    if (whole.width >= size.width && whole.height >= size.height) {
      // Widen the view back to the whole allocation, then take its top-left block.
      buffer.adjustROI(offset.y, whole.height - offset.y - buffer.rows, offset.x,
                       whole.width - offset.x - buffer.cols);
      buffer = buffer(cv::Rect(cv::Point(0, 0), size));
      return;
    }
  }
  const cv::Size allocate(std::max(size.width, capacity.width), std::max(size.height, capacity.height));
  const cv::Mat whole(allocate, CV_8UC1);
  buffer = whole(cv::Rect(cv::Point(0, 0), size));
}

}  // namespace imagepro
