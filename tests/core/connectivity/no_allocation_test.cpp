// Steady state of the real-time stages: once the output containers and workspaces
// have grown to a frame's size, Laplace edges and both connectivity methods allocate
// nothing more. Counts every global operator new in this test program
// (support/allocation_counter.cpp).
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "core/connectivity/connectivity.h"
#include "core/edges/edges.h"
#include "support/allocation_counter.h"

namespace imagepro {
namespace {

cv::Mat clutteredFrame(int shift) {
  cv::Mat binary(480, 640, CV_8UC1, cv::Scalar(0));
  cv::ellipse(binary, {320 + shift, 240}, {120, 90}, 20, 0, 360, cv::Scalar(255), cv::FILLED);
  cv::circle(binary, {320 + shift, 240}, 12, cv::Scalar(0), cv::FILLED);
  cv::circle(binary, {370 + shift, 240}, 12, cv::Scalar(0), cv::FILLED);
  for (int i = 0; i < 12; ++i)
    cv::rectangle(binary, cv::Rect(20 + 50 * i, 20 + 7 * i + shift, 30, 80), cv::Scalar(255), cv::FILLED);
  return binary;
}

TEST(SteadyState, EdgesAndConnectivityDoNotAllocate) {
  const cv::Mat first = clutteredFrame(0);
  const cv::Mat second = clutteredFrame(3);
  const cv::Size size = first.size();
  EdgeList edges;
  ConnectivityWorkspace ws;
  Paths paths;
  // Warm up on both frames so every buffer has its steady-state capacity.
  for (const cv::Mat* frame : {&first, &second}) {
    ASSERT_EQ(detectEdgesLaplace(*frame, edges), Status::Ok);
    ASSERT_EQ(connectCN1(edges, size, paths, ws), Status::Ok);
    ASSERT_EQ(connectCN0(edges, size, paths, ws), Status::Ok);
  }
  for (int i = 0; i < 4; ++i) {
    const cv::Mat& frame = i % 2 ? second : first;
    const long before = test::allocationCount();
    const Status e = detectEdgesLaplace(frame, edges);
    const Status c1 = connectCN1(edges, size, paths, ws);
    const Status c0 = connectCN0(edges, size, paths, ws);
    const long allocations = test::allocationCount() - before;
    ASSERT_EQ(e, Status::Ok);
    ASSERT_EQ(c1, Status::Ok);
    ASSERT_EQ(c0, Status::Ok);
    EXPECT_EQ(allocations, 0) << "frame " << i;
    EXPECT_GT(paths.pathCount(), 10u);
  }
}

}  // namespace
}  // namespace imagepro
