#include "core/segmentation/local_threshold.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>


namespace imagepro {
namespace {

// The rule of local_threshold.h evaluated plainly: the window's mean in double precision
// over replicated borders.
cv::Mat reference(const cv::Mat& grey, const BinarizationOptions& o) {
  const int half = localWindowPx(o, grey.size()) / 2;
  cv::Mat out(grey.size(), CV_8UC1);
  for (int y = 0; y < grey.rows; ++y)
    for (int x = 0; x < grey.cols; ++x) {
      double sum = 0;
      for (int dy = -half; dy <= half; ++dy)
        for (int dx = -half; dx <= half; ++dx)
          sum += grey.at<std::uint8_t>(std::clamp(y + dy, 0, grey.rows - 1), std::clamp(x + dx, 0, grey.cols - 1));
      const double mean = sum / ((2 * half + 1) * (2 * half + 1));
      const double drop = std::max(mean * o.offset, double(o.min_contrast));
      out.at<std::uint8_t>(y, x) = grey.at<std::uint8_t>(y, x) + drop < mean ? 0 : 255;
    }
  return out;
}

TEST(LocalThreshold, WindowFollowsTheImageWidthAndIsOdd) {
  BinarizationOptions o;
  EXPECT_EQ(localWindowPx(o, {640, 480}), 41);
  EXPECT_EQ(localWindowPx(o, {1920, 1080}), 121);
  EXPECT_EQ(localWindowPx(o, {100, 80}), 15);
  o.window_px = 20;
  EXPECT_EQ(localWindowPx(o, {640, 480}), 21);
}

TEST(LocalThreshold, MatchesThePlainRuleOnRandomImages) {
  std::mt19937 rng(3);
  for (const cv::Size size : {cv::Size(37, 23), cv::Size(64, 48), cv::Size(9, 70)}) {
    cv::Mat grey(size, CV_8UC1);
    cv::randu(grey, 0, 256);
    cv::GaussianBlur(grey, grey, cv::Size(5, 5), 1.5);
    BinarizationOptions o;
    o.window_px = 15;
    o.offset = 0.1;
    o.min_contrast = 3;
    LocalThresholdWorkspace ws;
    cv::Mat binary;
    binarizeLocal(grey, o, ws, binary);
    const cv::Mat expected = reference(grey, o);
    // Single precision against double: a pixel within a rounding of the limit may differ.
    EXPECT_LE(cv::countNonZero(binary != expected), 2) << size;
  }
}

TEST(LocalThreshold, FlatAreasOfAnyBrightnessAreWhiteEvenWithNoise) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 2.5);  // min_contrast is about 5 sigma
  for (const int level : {8, 30, 128, 240}) {
    cv::Mat grey(60, 80, CV_8UC1);
    for (int y = 0; y < grey.rows; ++y)
      for (int x = 0; x < grey.cols; ++x)
        grey.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(level + noise(rng));
    LocalThresholdWorkspace ws;
    cv::Mat binary;
    binarizeLocal(grey, BinarizationOptions{}, ws, binary);
    EXPECT_EQ(cv::countNonZero(binary), grey.rows * grey.cols) << level;
  }
}

// A white disk on its black card in the shade, darker than the lit wall behind it and far
// darker than a window beside it: against its neighbourhood it stays white and its card
// black (the pipeline's test of the same scene, stage_chain_test, shows the global
// threshold losing it).
TEST(LocalThreshold, FindsADimDiskBesideABrightWindow) {
  constexpr int kDisk = 70;
  cv::Mat grey(240, 320, CV_8UC1, cv::Scalar(120));
  grey(cv::Rect(160, 0, 160, 240)).setTo(250);
  cv::rectangle(grey, cv::Rect(40, 80, 80, 80), cv::Scalar(8), cv::FILLED);
  cv::circle(grey, {80, 120}, 30, cv::Scalar(kDisk), cv::FILLED, cv::LINE_AA);
  LocalThresholdWorkspace ws;
  cv::Mat binary;
  binarizeLocal(grey, BinarizationOptions{}, ws, binary);
  EXPECT_EQ(binary.at<std::uint8_t>(120, 80), 255);  // disk centre
  EXPECT_EQ(binary.at<std::uint8_t>(120, 65), 255);  // inside the rim
  EXPECT_EQ(binary.at<std::uint8_t>(120, 45), 0);    // card beside the disk
  EXPECT_EQ(binary.at<std::uint8_t>(85, 80), 0);     // card above it
  EXPECT_EQ(binary.at<std::uint8_t>(20, 240), 255);  // the window is flat: white
}

TEST(LocalThreshold, EmptyOrWrongTypeGivesEmpty) {
  LocalThresholdWorkspace ws;
  cv::Mat binary(3, 3, CV_8UC1);
  binarizeLocal(cv::Mat(), BinarizationOptions{}, ws, binary);
  EXPECT_TRUE(binary.empty());
  binarizeLocal(cv::Mat(4, 4, CV_16UC1, cv::Scalar(3)), BinarizationOptions{}, ws, binary);
  EXPECT_TRUE(binary.empty());
}

}  // namespace
}  // namespace imagepro
