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

bool samePixels(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

TEST(Histogram, MatchesBruteForceCount) {
  // Odd widths exercise the tail after the four-pixel steps.
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

TEST(Histogram, EmptyOrWrongTypeGivesZeros) {
  Histogram h;
  h.fill(9);
  computeHistogram(cv::Mat(), h);
  EXPECT_EQ(h, Histogram{});
  h.fill(9);
  computeHistogram(cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(1)), h);
  EXPECT_EQ(h, Histogram{});
}

TEST(CropWithHistogram, InsideRoiCopiesAndCounts) {
  const cv::Mat image = randomImage(120, 160, 11);
  const cv::Rect roi(13, 21, 57, 40);
  cv::Mat crop;
  Histogram h;
  cropWithHistogram(image, roi, crop, h);
  EXPECT_TRUE(samePixels(crop, image(roi)));
  EXPECT_EQ(h, bruteForce(image(roi)));
}

TEST(CropWithHistogram, RoiPartlyOutsideIsClipped) {
  const cv::Mat image = randomImage(120, 160, 12);
  cv::Mat crop;
  Histogram h;
  // Overhangs the top-left and the bottom-right corner in turn.
  cropWithHistogram(image, cv::Rect(-10, -5, 40, 30), crop, h);
  EXPECT_TRUE(samePixels(crop, image(cv::Rect(0, 0, 30, 25))));
  EXPECT_EQ(h, bruteForce(image(cv::Rect(0, 0, 30, 25))));
  cropWithHistogram(image, cv::Rect(150, 100, 50, 50), crop, h);
  EXPECT_TRUE(samePixels(crop, image(cv::Rect(150, 100, 10, 20))));
  EXPECT_EQ(h, bruteForce(image(cv::Rect(150, 100, 10, 20))));
}

TEST(CropWithHistogram, RoiOutsideGivesEmptyCrop) {
  const cv::Mat image = randomImage(20, 20, 13);
  cv::Mat crop;
  Histogram h;
  h.fill(5);
  cropWithHistogram(image, cv::Rect(30, 30, 10, 10), crop, h);
  EXPECT_TRUE(crop.empty());
  EXPECT_EQ(h, Histogram{});
  cropWithHistogram(cv::Mat(), cv::Rect(0, 0, 10, 10), crop, h);
  EXPECT_TRUE(crop.empty());
  EXPECT_EQ(h, Histogram{});
}

TEST(CropWithHistogram, ReusesTheCropAllocationAsTheRegionChanges) {
  const cv::Mat image = randomImage(240, 320, 14);
  cv::Mat crop;
  Histogram h;
  cropWithHistogram(image, cv::Rect(10, 10, 50, 40), crop, h);
  const std::uint8_t* allocation = crop.datastart;
  for (const cv::Rect roi : {cv::Rect(100, 60, 200, 150), cv::Rect(0, 0, 320, 240), cv::Rect(5, 9, 17, 3),
                             cv::Rect(-40, 200, 100, 100)}) {
    cropWithHistogram(image, roi, crop, h);
    const cv::Rect clipped = roi & cv::Rect(0, 0, 320, 240);
    EXPECT_EQ(crop.datastart, allocation) << roi;
    EXPECT_TRUE(samePixels(crop, image(clipped))) << roi;
    EXPECT_EQ(h, bruteForce(image(clipped))) << roi;
  }
}

TEST(CropWithHistogram, NeverWritesIntoTheFrame) {
  const cv::Mat image = randomImage(60, 80, 15);
  const cv::Mat original = image.clone();
  cv::Mat crop = image;  // a crop buffer that is the frame itself
  Histogram h;
  cropWithHistogram(image, cv::Rect(20, 10, 30, 30), crop, h);
  EXPECT_TRUE(samePixels(image, original));
  EXPECT_TRUE(samePixels(crop, original(cv::Rect(20, 10, 30, 30))));
}

}  // namespace
}  // namespace imagepro
