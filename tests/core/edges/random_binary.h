#pragma once
// Seeded random binary images for the edge and connectivity property tests: filled
// rectangles and ellipses (some with black holes), one-pixel lines and salt noise.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <random>

namespace imagepro::testing {

inline int uniformInt(std::mt19937& rng, int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); }

// A CV_8UC1 image of 0 and `white` (any nonzero value stands for white).
inline cv::Mat randomBinary(std::mt19937& rng, cv::Size size, int white = 255) {
  cv::Mat img(size, CV_8UC1, cv::Scalar(0));
  const int w = size.width, h = size.height;
  const int shapes = uniformInt(rng, 0, 6);
  for (int i = 0; i < shapes; ++i) {
    const int kind = uniformInt(rng, 0, 4);
    const cv::Point c(uniformInt(rng, -w / 4, w + w / 4), uniformInt(rng, -h / 4, h + h / 4));
    const int colour = uniformInt(rng, 0, 4) == 0 ? 0 : white;  // now and then a black hole
    if (kind == 0) {
      const cv::Point d(uniformInt(rng, 0, w / 2 + 1), uniformInt(rng, 0, h / 2 + 1));
      cv::rectangle(img, c - d, c + d, cv::Scalar(colour), cv::FILLED);
    } else if (kind <= 2) {
      const cv::Size axes(uniformInt(rng, 0, w / 2 + 1), uniformInt(rng, 0, h / 2 + 1));
      cv::ellipse(img, c, axes, uniformInt(rng, 0, 179), 0, 360, cv::Scalar(colour), cv::FILLED);
    } else if (kind == 3) {
      const cv::Point e(uniformInt(rng, 0, w - 1), uniformInt(rng, 0, h - 1));
      cv::line(img, c, e, cv::Scalar(uniformInt(rng, 0, 1) ? white : 0), 1, cv::LINE_8);
    } else {
      const int dots = uniformInt(rng, 0, w * h / 8 + 1);
      for (int k = 0; k < dots; ++k)
        img.at<std::uint8_t>(uniformInt(rng, 0, h - 1), uniformInt(rng, 0, w - 1)) =
            static_cast<std::uint8_t>(uniformInt(rng, 0, 1) ? white : 0);
    }
  }
  return img;
}

}  // namespace imagepro::testing
