#include "core/segmentation/histogram.h"

#include <gtest/gtest.h>

#include <random>

namespace imagepro {
namespace {

cv::Mat randomImage(int rows, int cols, unsigned seed) {
  cv::Mat image(rows, cols, CV_8UC1);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(0, 255);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) image.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(level(rng));
  return image;
}

Histogram bruteForce(const cv::Mat& image) {
  Histogram h{};
  for (int r = 0; r < image.rows; ++r)
    for (int c = 0; c < image.cols; ++c) ++h[image.at<std::uint8_t>(r, c)];
  return h;
}

TEST(Histogram, MatchesBruteForceCount) {
  // Odd sizes exercise the steps that end a row.
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(1, 1), cv::Size(7, 3), cv::Size(3, 101)}) {
    const cv::Mat image = randomImage(size.height, size.width, 7u + static_cast<unsigned>(size.area()));
    Histogram h;
    computeHistogram(image, h);
    EXPECT_EQ(h, bruteForce(image)) << size;
  }
}

TEST(Histogram, CountsANonContinuousView) {
  const cv::Mat image = randomImage(50, 61, 3);
  const cv::Mat view = image(cv::Rect(5, 7, 33, 20));
  ASSERT_FALSE(view.isContinuous());
  Histogram h;
  computeHistogram(view, h);
  EXPECT_EQ(h, bruteForce(view));
}

// Every k-th row of a view, from the first, each count times k; a step of 1 or less is
// the exact histogram; bad input all zeros.
TEST(Histogram, EstimateFromEveryKthRow) {
  const cv::Mat image = randomImage(120, 97, 11);
  const cv::Mat view = image(cv::Rect(3, 5, 80, 101));
  for (const int k : {2, 3, 7}) {
    Histogram expected{};
    for (int r = 0; r < view.rows; r += k)
      for (int c = 0; c < view.cols; ++c) expected[view.at<std::uint8_t>(r, c)] += static_cast<std::uint32_t>(k);
    Histogram h;
    estimateHistogramFromRows(view, k, h);
    EXPECT_EQ(h, expected) << "k " << k;
  }
  Histogram h;
  for (const int k : {1, 0, -2}) {
    estimateHistogramFromRows(view, k, h);
    EXPECT_EQ(h, bruteForce(view)) << "k " << k;
  }
  h.fill(9);
  estimateHistogramFromRows(cv::Mat(), 3, h);
  EXPECT_EQ(h, Histogram{});
}

TEST(Histogram, EmptyOrWrongTypeGivesZeros) {
  Histogram h;
  h.fill(9);
  computeHistogram(cv::Mat(), h);
  EXPECT_EQ(h, Histogram{});
  h.fill(9);
  computeHistogram(cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(1)), h);
  EXPECT_EQ(h, Histogram{});
  h.fill(9);
  const int sizes[] = {2, 3, 4};
  computeHistogram(cv::Mat(3, sizes, CV_8UC1, cv::Scalar::all(1)), h);
  EXPECT_EQ(h, Histogram{});
}

// Region views of every width from 1 to 70 pixels (the sixteen-, eight-, four- and
// one-pixel steps, the rows fetched ahead) and of the frame's full width less one, at
// odd offsets, with fewer and more rows than are fetched ahead.
TEST(Histogram, CountsRegionViewsOfEveryShape) {
  const cv::Mat image = randomImage(240, 320, 16);
  for (int width = 1; width <= 70; ++width)
    for (const int height : {1, 2, 9, 131}) {
      const cv::Mat view = image(cv::Rect(320 - width - width % 3, 5 + width % 7, width, height));
      Histogram h;
      computeHistogram(view, h);
      ASSERT_EQ(h, bruteForce(view)) << width << " x " << height;
    }
  for (const cv::Rect roi : {cv::Rect(1, 3, 319, 200), cv::Rect(0, 0, 319, 240), cv::Rect(0, 10, 320, 30)}) {
    Histogram h;
    computeHistogram(image(roi), h);
    EXPECT_EQ(h, bruteForce(image(roi))) << roi;
  }
}

// Runs of one grey level land in the same partial histograms: the sums must still add up.
TEST(Histogram, CountsUniformRegions) {
  cv::Mat image(100, 200, CV_8UC1, cv::Scalar::all(255));
  image(cv::Rect(0, 50, 200, 50)).setTo(0);
  const cv::Mat view = image(cv::Rect(3, 40, 141, 30));
  Histogram h;
  computeHistogram(view, h);
  Histogram expected{};
  expected[255] = 141 * 10;
  expected[0] = 141 * 20;
  EXPECT_EQ(h, expected);
}

TEST(Histogram, EmptyRegionViewGivesZeros) {
  const cv::Mat image = randomImage(20, 20, 13);
  Histogram h;
  h.fill(5);
  computeHistogram(image(cv::Rect(30, 30, 10, 10) & cv::Rect(0, 0, 20, 20)), h);
  EXPECT_EQ(h, Histogram{});
}

}  // namespace
}  // namespace imagepro
