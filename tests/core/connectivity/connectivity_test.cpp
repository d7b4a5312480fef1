#include "core/connectivity/connectivity.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <random>

#include "../edges/random_binary.h"
#include "core/edges/edges.h"

namespace imagepro {
namespace {

using testing::randomBinary;
using testing::uniformInt;

bool samePixel(const EdgePixel& a, const EdgePixel& b) {
  return a.x == b.x && a.y == b.y && a.gx == b.gx && a.gy == b.gy;
}

bool rasterBefore(const EdgePixel& a, const EdgePixel& b) { return a.y != b.y ? a.y < b.y : a.x < b.x; }

void expectIdentical(const Paths& a, const Paths& b, const std::string& what) {
  ASSERT_EQ(a.starts, b.starts) << what;
  ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) ASSERT_TRUE(samePixel(a.pixels[i], b.pixels[i])) << what << " pixel " << i;
}

// Checks `paths` against an independent ground truth, OpenCV's 8-connected
// component labelling of the edge pixels:
//  - every edge pixel (with its gradient) is in exactly one path;
//  - the paths are exactly the 8-connected components (8-neighbours share a path,
//    a path is one component);
//  - canonical order: paths ordered by their earliest pixel in the input list, each
//    starting with that pixel.
void expectValidPartition(const EdgeList& edges, cv::Size size, const Paths& paths, const std::string& what) {
  ASSERT_EQ(paths.starts.front(), 0u) << what;
  ASSERT_EQ(paths.starts.back(), paths.pixels.size()) << what;
  ASSERT_TRUE(std::is_sorted(paths.starts.begin(), paths.starts.end())) << what;
  for (std::size_t i = 0; i < paths.pathCount(); ++i) ASSERT_LT(paths.starts[i], paths.starts[i + 1]) << what << " empty path";

  auto byPosition = [](const EdgePixel& a, const EdgePixel& b) { return rasterBefore(a, b); };
  EdgeList sortedIn = edges, sortedOut = paths.pixels;
  std::sort(sortedIn.begin(), sortedIn.end(), byPosition);
  std::sort(sortedOut.begin(), sortedOut.end(), byPosition);
  ASSERT_EQ(sortedIn.size(), sortedOut.size()) << what;
  for (std::size_t i = 0; i < sortedIn.size(); ++i) ASSERT_TRUE(samePixel(sortedIn[i], sortedOut[i])) << what;

  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  for (const auto& p : edges) mask.at<std::uint8_t>(p.y, p.x) = 255;
  cv::Mat components;
  const int count = cv::connectedComponents(mask, components, 8, CV_32S) - 1;
  ASSERT_EQ(static_cast<int>(paths.pathCount()), count) << what;
  std::vector<int> pathOfComponent(static_cast<std::size_t>(count) + 1, -1);
  for (std::size_t i = 0; i < paths.pathCount(); ++i)
    for (const auto& p : paths.path(i)) {
      int& owner = pathOfComponent[static_cast<std::size_t>(components.at<int>(p.y, p.x))];
      if (owner == -1) owner = static_cast<int>(i);
      ASSERT_EQ(owner, static_cast<int>(i)) << what << ": a component split over two paths";
    }

  cv::Mat order(size, CV_32SC1, cv::Scalar(-1));
  for (std::size_t i = 0; i < edges.size(); ++i) order.at<int>(edges[i].y, edges[i].x) = static_cast<int>(i);
  int previousFirst = -1;
  for (std::size_t i = 0; i < paths.pathCount(); ++i) {
    const auto path = paths.path(i);
    const int first = order.at<int>(path.front().y, path.front().x);
    for (const auto& p : path) ASSERT_LE(first, order.at<int>(p.y, p.x)) << what;
    ASSERT_GT(first, previousFirst) << what;
    previousFirst = first;
  }
}

// ---------------------------------------------------------------- properties

TEST(Connectivity, CN0AndCN1GiveTheSamePartitionOnRandomImages) {
  std::mt19937 rng(31337);
  EdgeList edges;
  EdgeWorkspace edgeWs;
  ConnectivityWorkspace ws0, ws1;
  Paths cn0, cn1;
  int nonTrivial = 0;
  for (int i = 0; i < 4000; ++i) {
    const cv::Size size(uniformInt(rng, 1, 100), uniformInt(rng, 1, 80));
    const cv::Mat binary = randomBinary(rng, size);
    const EdgeMethod method = i % 4 == 3 ? EdgeMethod::SobelThinning : EdgeMethod::Laplace;
    const Status edgeStatus = detectEdges(method, binary, edges, edgeWs);
    if (i % 5 == 4) std::shuffle(edges.begin(), edges.end(), rng);  // not in raster order
    const Status s0 = connectCN0(edges, size, cn0, ws0);
    const Status s1 = connectCN1(edges, size, cn1, ws1);
    const std::string what = "image " + std::to_string(i);
    if (edgeStatus == Status::NoEdges) {
      ASSERT_EQ(s0, Status::NoEdges) << what;
      ASSERT_EQ(s1, Status::NoEdges) << what;
      ASSERT_EQ(cn0.pathCount(), 0u);
      ASSERT_EQ(cn1.pathCount(), 0u);
      continue;
    }
    ASSERT_EQ(s0, Status::Ok) << what;
    ASSERT_EQ(s1, Status::Ok) << what;
    expectIdentical(cn0, cn1, what);
    expectValidPartition(edges, size, cn1, what);
    if (cn1.pathCount() > 1) ++nonTrivial;
  }
  EXPECT_GT(nonTrivial, 1000);  // the generator does produce images with several paths
}

TEST(Connectivity, EachBlobContourIsOnePath) {
  cv::Mat binary(120, 160, CV_8UC1, cv::Scalar(0));
  cv::circle(binary, {40, 40}, 25, cv::Scalar(255), cv::FILLED);
  cv::circle(binary, {40, 40}, 6, cv::Scalar(0), cv::FILLED);  // a spot: its own contour
  cv::rectangle(binary, cv::Rect(90, 20, 50, 70), cv::Scalar(255), cv::FILLED);
  cv::line(binary, {10, 100}, {150, 110}, cv::Scalar(255));
  EdgeList edges;
  ASSERT_EQ(detectEdgesLaplace(binary, edges), Status::Ok);
  ConnectivityWorkspace ws;
  Paths paths;
  for (const auto m : {ConnectivityMethod::CN0, ConnectivityMethod::CN1}) {
    ASSERT_EQ(connectPaths(m, edges, binary.size(), paths, ws), Status::Ok);
    ASSERT_EQ(paths.pathCount(), 4u);
    // Canonical order: by first pixel in raster order, each path starting there.
    EXPECT_EQ(paths.path(0).front().y, 15);   // disk top
    EXPECT_EQ(paths.path(1).front().y, 20);   // rectangle top-left corner
    EXPECT_EQ(paths.path(1).front().x, 90);
    EXPECT_EQ(paths.path(1).size(), static_cast<std::size_t>(2 * (50 + 70) - 4));
    EXPECT_EQ(paths.path(2).front().y, 33);   // white pixel above the spot
    EXPECT_EQ(paths.path(3).front().y, 100);  // line start
    expectValidPartition(edges, binary.size(), paths, "blobs");
  }
}

// No path length limit: one huge outline stays one path.
TEST(Connectivity, HugeOutlineIsNotSplit) {
  cv::Mat binary(480, 640, CV_8UC1, cv::Scalar(0));
  binary(cv::Rect(20, 20, 600, 440)).setTo(255);
  EdgeList edges;
  ASSERT_EQ(detectEdgesLaplace(binary, edges), Status::Ok);
  ASSERT_EQ(edges.size(), static_cast<std::size_t>(2 * (600 + 440) - 4));
  ConnectivityWorkspace ws;
  Paths paths;
  for (const auto m : {ConnectivityMethod::CN0, ConnectivityMethod::CN1}) {
    ASSERT_EQ(connectPaths(m, edges, binary.size(), paths, ws), Status::Ok);
    ASSERT_EQ(paths.pathCount(), 1u);
    EXPECT_EQ(paths.pixels.size(), edges.size());
  }
}

// A serpentine line through the whole frame: one path of over 100 000 pixels (CN1),
// and a smaller one of about 10 000 for the quadratic CN0.
TEST(Connectivity, LongSerpentineIsOnePath) {
  auto serpentine = [](cv::Size size) {
    cv::Mat binary(size, CV_8UC1, cv::Scalar(0));
    for (int y = 1, k = 0; y + 1 < size.height; y += 2, ++k) {
      cv::line(binary, {1, y}, {size.width - 2, y}, cv::Scalar(255));
      if (y + 2 < size.height - 1) {
        const int x = k % 2 ? 1 : size.width - 2;
        binary.at<std::uint8_t>(y + 1, x) = 255;
      }
    }
    return binary;
  };
  EdgeList edges;
  ConnectivityWorkspace ws;
  Paths paths;
  const cv::Mat big = serpentine({640, 480});
  ASSERT_EQ(detectEdgesLaplace(big, edges), Status::Ok);
  ASSERT_GT(edges.size(), 100000u);
  ASSERT_EQ(connectCN1(edges, big.size(), paths, ws), Status::Ok);
  EXPECT_EQ(paths.pathCount(), 1u);
  EXPECT_EQ(paths.pixels.size(), edges.size());

  const cv::Mat small = serpentine({200, 100});
  ASSERT_EQ(detectEdgesLaplace(small, edges), Status::Ok);
  ASSERT_GT(edges.size(), 9000u);
  Paths cn0;
  ASSERT_EQ(connectCN0(edges, small.size(), cn0, ws), Status::Ok);
  ASSERT_EQ(connectCN1(edges, small.size(), paths, ws), Status::Ok);
  EXPECT_EQ(cn0.pathCount(), 1u);
  expectIdentical(cn0, paths, "serpentine");
}

// ---------------------------------------------------------------- bad input

TEST(Connectivity, BadInputGivesNamedStatusAndLeavesWorkspaceUsable) {
  const cv::Size size(20, 10);
  const EdgeList good = {{3, 3, 0, 0}, {4, 4, 0, 0}, {10, 5, 0, 0}};
  ConnectivityWorkspace ws;
  Paths paths;
  for (const auto m : {ConnectivityMethod::CN0, ConnectivityMethod::CN1}) {
    paths.pixels.assign(2, EdgePixel{});
    paths.starts = {0, 2};
    EXPECT_EQ(connectPaths(m, {}, size, paths, ws), Status::NoEdges);
    EXPECT_EQ(paths.pathCount(), 0u);
    EXPECT_EQ(connectPaths(m, good, {0, 10}, paths, ws), Status::EmptyFrame);
    EXPECT_EQ(connectPaths(m, good, {-5, 10}, paths, ws), Status::EmptyFrame);
    for (const EdgePixel bad : {EdgePixel{20, 0, 0, 0}, EdgePixel{0, 10, 0, 0}, EdgePixel{-1, 2, 0, 0},
                                EdgePixel{2, -1, 0, 0}, EdgePixel{4, 4, 1, 1}}) {
      EdgeList edges = good;
      edges.push_back(bad);  // out of the image, or a repeat of (4, 4)
      EXPECT_EQ(connectPaths(m, edges, size, paths, ws), Status::InvalidEdgeList) << bad.x << "," << bad.y;
      EXPECT_EQ(paths.pathCount(), 0u);
      EXPECT_TRUE(paths.pixels.empty());
    }
    // The failed calls left nothing behind in the workspace.
    ASSERT_EQ(connectPaths(m, good, size, paths, ws), Status::Ok);
    ASSERT_EQ(paths.pathCount(), 2u);
    EXPECT_EQ(paths.path(0).size(), 2u);
    // A different image size with the same workspace.
    const EdgeList corner = {{0, 0, 0, 0}, {1, 1, 0, 0}, {0, 2, 0, 0}};
    ASSERT_EQ(connectPaths(m, corner, {2, 3}, paths, ws), Status::Ok);
    EXPECT_EQ(paths.pathCount(), 1u);
  }
}

// Lists in raster order take a faster check (four pixels at a time, then one by one):
// a bad entry at any position of either part is still named, leaves nothing behind, and
// a list that leaves raster order part-way is still grouped like CN0 does.
TEST(Connectivity, RasterOrderedListsAreCheckedAtEveryPosition) {
  const cv::Size size(40, 30);
  EdgeList raster;
  for (int y = 2; y < 28; y += 5)
    for (int x = 3; x < 37; x += 3) raster.push_back({static_cast<std::int16_t>(x), static_cast<std::int16_t>(y), 1, 2});
  ASSERT_EQ(raster.size() % 4, 0u);
  raster.push_back({38, 28, 0, 0});  // a tail past the last whole group of four
  ConnectivityWorkspace ws, ws0;
  Paths paths, cn0;
  ASSERT_EQ(connectCN1(raster, size, paths, ws), Status::Ok);
  expectValidPartition(raster, size, paths, "raster");
  for (std::size_t at = 0; at < raster.size(); ++at) {
    const std::string where = "entry " + std::to_string(at);
    for (const auto& [bad, name] : std::vector<std::pair<EdgePixel, std::string>>{
             {{40, raster[at].y, 0, 0}, "column past the edge"},
             {{-1, raster[at].y, 0, 0}, "negative column"},
             {{raster[at].x, -1, 0, 0}, "negative row"},
             {{raster[at].x, 30, 0, 0}, "row past the edge"},
             {at > 0 ? raster[at - 1] : raster[1], "repeat"}}) {
      EdgeList edges = raster;
      edges[at] = bad;
      EXPECT_EQ(connectCN1(edges, size, paths, ws), Status::InvalidEdgeList) << where << ", " << name;
      EXPECT_EQ(paths.pathCount(), 0u);
      EXPECT_TRUE(paths.pixels.empty());
    }
    // Valid, but out of raster order from here on: two pixels swapped.
    if (at + 1 < raster.size()) {
      EdgeList edges = raster;
      std::swap(edges[at], edges[at + 1]);
      ASSERT_EQ(connectCN1(edges, size, paths, ws), Status::Ok) << where;
      ASSERT_EQ(connectCN0(edges, size, cn0, ws0), Status::Ok) << where;
      expectIdentical(cn0, paths, where);
      expectValidPartition(edges, size, paths, where);
    }
  }
  // The failed calls left the index image clean: the first list again gives its paths.
  ASSERT_EQ(connectCN1(raster, size, paths, ws), Status::Ok);
  expectValidPartition(raster, size, paths, "raster again");
}

// Index-image rows longer than 32767 entries, too long for the four-at-a-time offsets
// (16-bit products), are indexed one by one.
TEST(Connectivity, VeryWideImagesAreGroupedToo) {
  const cv::Size size(32767, 3);
  EdgeList edges;
  for (int x = 0; x < 12; ++x) edges.push_back({static_cast<std::int16_t>(32750 + x), 1, 0, 0});
  edges.push_back({5, 2, 0, 0});
  std::sort(edges.begin(), edges.end(), rasterBefore);
  ConnectivityWorkspace ws, ws0;
  Paths paths, cn0;
  ASSERT_EQ(connectCN1(edges, size, paths, ws), Status::Ok);
  ASSERT_EQ(connectCN0(edges, size, cn0, ws0), Status::Ok);
  EXPECT_EQ(paths.pathCount(), 2u);
  expectIdentical(cn0, paths, "wide");
}

// A path index past the end would read beyond the pixels: a build with the core's checks
// on stops there with the check's message.
TEST(Connectivity, PathIndexPastTheEndIsAContractViolation) {
#if defined(NDEBUG) && !defined(IMAGEPRO_CONTRACTS)
  GTEST_SKIP() << "the checks compile to nothing here (a release build without -DIMAGEPRO_CONTRACTS=ON)";
#else
  Paths paths;
  paths.pixels.assign(3, EdgePixel{});
  paths.starts = {0, 3};
  EXPECT_EQ(paths.path(0).size(), 3u);
  EXPECT_DEATH(paths.path(1), "path index below pathCount");
#endif
}

}  // namespace
}  // namespace imagepro
