#include "core/segmentation/reduce.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace imagepro {
namespace {

cv::Mat randomImage(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(0, 255);
  cv::Mat image(rows, cols, CV_8UC1);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(level(rng));
  return image;
}

// The block's mean in double precision, rounded half up.
int plainMean(const cv::Mat& grey, int k, int y, int x) {
  double sum = 0;
  for (int r = 0; r < k; ++r)
    for (int c = 0; c < k; ++c) sum += grey.at<std::uint8_t>(y * k + r, x * k + c);
  return static_cast<int>(std::floor(sum / (k * k) + 0.5));
}

TEST(Reduce, EveryFactorGivesTheBlocksRoundedMean) {
  // Sides that no factor divides: the last partial blocks are left out (and at factor 2
  // the vector loop's 16 outputs a step leave a tail of 2).
  const cv::Mat grey = randomImage(61, 101, 7);
  std::vector<std::uint16_t> ws;
  cv::Mat out;
  for (int k = 1; k <= kMaxReduceFactor; ++k) {
    reduceByBlockMean(grey, k, out, ws);
    ASSERT_EQ(out.cols, 101 / k) << "factor " << k;
    ASSERT_EQ(out.rows, 61 / k) << "factor " << k;
    for (int y = 0; y < out.rows; ++y)
      for (int x = 0; x < out.cols; ++x)
        ASSERT_EQ(out.at<std::uint8_t>(y, x), plainMean(grey, k, y, x)) << "factor " << k << " at " << x << "," << y;
  }
}

// Every block sum a factor can give (0 to 255 k^2), one block each: the division by
// multiplication rounds each like the exact division, half up.
TEST(Reduce, EveryBlockSumRoundsLikeTheExactDivision) {
  std::vector<std::uint16_t> ws;
  cv::Mat out;
  for (int k = 2; k <= kMaxReduceFactor; ++k) {
    const int n = k * k, sums = 255 * n + 1;
    cv::Mat grey(k, sums * k, CV_8UC1);
    for (int j = 0; j < sums; ++j)
      for (int i = 0; i < n; ++i)  // j / n in every pixel, one more in j % n of them
        grey.at<std::uint8_t>(i / k, j * k + i % k) = static_cast<std::uint8_t>(j / n + (i < j % n ? 1 : 0));
    reduceByBlockMean(grey, k, out, ws);
    ASSERT_EQ(out.cols, sums);
    for (int j = 0; j < sums; ++j) ASSERT_EQ(out.at<std::uint8_t>(0, j), (j + n / 2) / n) << "factor " << k << ", sum " << j;
  }
}

TEST(Reduce, TheLargestBlockSumsAreExact) {
  // All white, and white but for one level: the sums at the top of the 16-bit range.
  std::vector<std::uint16_t> ws;
  cv::Mat out;
  cv::Mat white(45, 45, CV_8UC1, cv::Scalar(255));
  reduceByBlockMean(white, kMaxReduceFactor, out, ws);
  ASSERT_EQ(out.size(), cv::Size(3, 3));
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 255);
  white.at<std::uint8_t>(0, 0) = 0;  // 255 * 224 / 225 = 253.87
  reduceByBlockMean(white, kMaxReduceFactor, out, ws);
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 254);
}

TEST(Reduce, AViewIsReducedAndTheBufferKept) {
  const cv::Mat frame = randomImage(120, 160, 3);
  const cv::Mat view = frame(cv::Rect(11, 7, 90, 64));
  std::vector<std::uint16_t> ws;
  cv::Mat out;
  reduceByBlockMean(view, 3, out, ws);
  ASSERT_EQ(out.size(), cv::Size(30, 21));
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x) ASSERT_EQ(out.at<std::uint8_t>(y, x), plainMean(view, 3, y, x));
  // Room for the whole frame: a later, larger reduction reuses the allocation.
  const std::uint8_t* const start = out.datastart;
  reduceByBlockMean(frame, 2, out, ws);
  EXPECT_EQ(out.size(), cv::Size(80, 60));
  EXPECT_EQ(out.datastart, start);
}

TEST(Reduce, WhatCannotBeReducedGivesAnEmptyImage) {
  std::vector<std::uint16_t> ws;
  cv::Mat out = randomImage(4, 4, 1);
  reduceByBlockMean(cv::Mat(), 2, out, ws);
  EXPECT_TRUE(out.empty());
  const cv::Mat grey = randomImage(20, 30, 2);
  for (const int k : {0, -1, kMaxReduceFactor + 1, 21, 31}) {
    out = randomImage(4, 4, 1);
    reduceByBlockMean(grey, k, out, ws);
    EXPECT_TRUE(out.empty()) << "factor " << k;
  }
  reduceByBlockMean(cv::Mat(20, 30, CV_16UC1, cv::Scalar(0)), 2, out, ws);
  EXPECT_TRUE(out.empty());
}

TEST(Reduce, TheCoarseFactorBringsAnyWidthToAbout320) {
  EXPECT_EQ(coarseFactor(639), 1);
  EXPECT_EQ(coarseFactor(640), 2);
  EXPECT_EQ(coarseFactor(1280), 4);
  EXPECT_EQ(coarseFactor(1920), 6);
  EXPECT_EQ(coarseFactor(100), 1);
  EXPECT_EQ(coarseFactor(0), 1);
  EXPECT_EQ(coarseFactor(100000), kMaxReduceFactor);
}

}  // namespace
}  // namespace imagepro
