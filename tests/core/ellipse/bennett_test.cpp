#include "core/ellipse/bennett.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "scenes.h"

namespace imagepro {
namespace {

// The longest path of a binary image.
std::span<const EdgePixel> longestPath(const test::PathPipeline& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < p.paths.pathCount(); ++i)
    if (p.paths.path(i).size() > p.paths.path(best).size()) best = i;
  return p.paths.path(best);
}

TEST(Bennett, PeakAtTheCentreOfAnEllipse) {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(0));
  cv::ellipse(img, cv::Point(300, 200), cv::Size(50, 30), 20.0, 0.0, 360.0, cv::Scalar(255), cv::FILLED);
  test::PathPipeline p;
  ASSERT_EQ(p.run(img, 128), Status::Ok);
  BennettWorkspace ws;
  BennettResult r;
  ASSERT_EQ(bennettAccumulate(longestPath(p), 0, ws, r), Status::Ok);
  EXPECT_NEAR(r.cx, 300.0, 1.0);
  EXPECT_NEAR(r.cy, 200.0, 1.0);
  EXPECT_GT(r.symmetry_px, r.border_distance_px);  // symmetric over the whole accumulator
  EXPECT_GT(r.peak_fraction, 0.0625);
  EXPECT_GT(r.quality, 0.0);
  EXPECT_TRUE(bennettAccepts(EllipseOptions{}, r));
}

TEST(Bennett, SubsampledPathKeepsThePeak) {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(0));
  cv::ellipse(img, cv::Point(320, 240), cv::Size(110, 70), -35.0, 0.0, 360.0, cv::Scalar(255), cv::FILLED);
  test::PathPipeline p;
  ASSERT_EQ(p.run(img, 128), Status::Ok);
  const auto path = longestPath(p);
  ASSERT_GT(path.size(), 256u);
  BennettWorkspace ws;
  BennettResult all, sampled;
  ASSERT_EQ(bennettAccumulate(path, 0, ws, all), Status::Ok);
  ASSERT_EQ(bennettAccumulate(path, 256, ws, sampled), Status::Ok);
  EXPECT_NEAR(sampled.cx, all.cx, 1.0);
  EXPECT_NEAR(sampled.cy, all.cy, 1.0);
  EXPECT_NEAR(sampled.peak_fraction / all.peak_fraction, 1.0, 0.25);
  EXPECT_LT(sampled.pairs, all.pairs);
}

TEST(Bennett, SquareAndHalfDiskRejected) {
  EllipseOptions o;
  BennettWorkspace ws;
  BennettResult r;
  test::PathPipeline p;
  cv::Mat square(480, 640, CV_8UC1, cv::Scalar(0));
  cv::rectangle(square, cv::Rect(250, 150, 90, 90), cv::Scalar(255), cv::FILLED);
  ASSERT_EQ(p.run(square, 128), Status::Ok);
  ASSERT_EQ(bennettAccumulate(longestPath(p), 0, ws, r), Status::Ok);
  EXPECT_FALSE(bennettAccepts(o, r));
  // A disk cut by the image border: its accumulator is not symmetric (thesis: Bennett
  // misses partial ellipses).
  cv::Mat cut(480, 640, CV_8UC1, cv::Scalar(0));
  cv::circle(cut, cv::Point(20, 240), 60, cv::Scalar(255), cv::FILLED);
  ASSERT_EQ(p.run(cut, 128), Status::Ok);
  ASSERT_EQ(bennettAccumulate(longestPath(p), 0, ws, r), Status::Ok);
  EXPECT_LE(r.symmetry_px, r.border_distance_px);
  EXPECT_FALSE(bennettAccepts(o, r));
}

TEST(Bennett, TooFewPointsAndNoVotes) {
  BennettWorkspace ws;
  BennettResult r;
  std::vector<EdgePixel> few{{1, 1, 1, 0}, {2, 1, 1, 0}, {3, 1, 1, 0}};
  EXPECT_EQ(bennettAccumulate(few, 0, ws, r), Status::TooFewPoints);
  std::vector<EdgePixel> flat;  // gradients but no tangent information across a line
  for (std::int16_t x = 0; x < 20; ++x) flat.push_back({x, 5, 0, 4});
  EXPECT_EQ(bennettAccumulate(flat, 0, ws, r), Status::NoTarget);
  std::vector<EdgePixel> no_gradient;
  for (std::int16_t x = 0; x < 20; ++x) no_gradient.push_back({x, static_cast<std::int16_t>(x % 3), 0, 0});
  EXPECT_EQ(bennettAccumulate(no_gradient, 0, ws, r), Status::TooFewPoints);
}

}  // namespace
}  // namespace imagepro
