#include "core/edges/edges.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <random>

#include "core/common/simd_level.h"
#include "random_binary.h"

namespace imagepro {
namespace {

using testing::randomBinary;
using testing::uniformInt;

cv::Mat maskOf(const EdgeList& edges, cv::Size size) {
  cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
  for (const auto& p : edges) mask.at<std::uint8_t>(p.y, p.x) = 255;
  return mask;
}

// Eq. 2.25 straight from its definition: a white pixel with a black 4-neighbour
// inside the image.
cv::Mat definitionLaplace(const cv::Mat& binary) {
  cv::Mat mask(binary.size(), CV_8UC1, cv::Scalar(0));
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int y = 0; y < binary.rows; ++y)
    for (int x = 0; x < binary.cols; ++x) {
      if (binary.at<std::uint8_t>(y, x) == 0) continue;
      for (int k = 0; k < 4; ++k) {
        const int nx = x + dx[k], ny = y + dy[k];
        if (nx >= 0 && ny >= 0 && nx < binary.cols && ny < binary.rows && binary.at<std::uint8_t>(ny, nx) == 0)
          mask.at<std::uint8_t>(y, x) = 255;
      }
    }
  return mask;
}

// Eqs. 2.19-2.20 by OpenCV on the 0/1 image with a replicated border.
void openCvSobel(const cv::Mat& binary, cv::Mat& gx, cv::Mat& gy) {
  cv::Mat b01 = binary != 0;
  b01 /= 255;
  cv::Sobel(b01, gx, CV_16S, 1, 0, 3, 1, 0, cv::BORDER_REPLICATE);
  cv::Sobel(b01, gy, CV_16S, 0, 1, 3, 1, 0, cv::BORDER_REPLICATE);
}

bool rasterOrdered(const EdgeList& edges) {
  for (std::size_t i = 1; i < edges.size(); ++i) {
    const auto &a = edges[i - 1], &b = edges[i];
    if (a.y > b.y || (a.y == b.y && a.x >= b.x)) return false;
  }
  return true;
}

void expectGradientsMatchOpenCv(const cv::Mat& binary, const EdgeList& edges) {
  cv::Mat gx, gy;
  openCvSobel(binary, gx, gy);
  for (const auto& p : edges) {
    ASSERT_EQ(p.gx, gx.at<std::int16_t>(p.y, p.x)) << "at " << p.x << "," << p.y;
    ASSERT_EQ(p.gy, gy.at<std::int16_t>(p.y, p.x)) << "at " << p.x << "," << p.y;
  }
}

int eightNeighboursInMask(const cv::Mat& mask, int x, int y) {
  int n = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if ((dx || dy) && nx >= 0 && ny >= 0 && nx < mask.cols && ny < mask.rows && mask.at<std::uint8_t>(ny, nx))
        ++n;
    }
  return n;
}

int eightComponents(const cv::Mat& mask) {
  cv::Mat labels;
  return cv::connectedComponents(mask, labels, 8, CV_32S) - 1;
}

// ---------------------------------------------------------------- input checks

TEST(Edges, EmptyOrWrongTypeIsEmptyFrame) {
  EdgeWorkspace ws;
  EdgeList out{{1, 2, 3, 4}};
  for (const EdgeMethod m : {EdgeMethod::Laplace, EdgeMethod::SobelThinning}) {
    EXPECT_EQ(detectEdges(m, cv::Mat(), out, ws), Status::EmptyFrame);
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(detectEdges(m, cv::Mat(10, 10, CV_8UC3, cv::Scalar::all(255)), out, ws), Status::EmptyFrame);
    EXPECT_EQ(detectEdges(m, cv::Mat(10, 10, CV_16UC1, cv::Scalar(0)), out, ws), Status::EmptyFrame);
    EXPECT_EQ(detectEdges(m, cv::Mat(1, 40000, CV_8UC1, cv::Scalar(0)), out, ws), Status::EmptyFrame);
  }
}

TEST(Edges, UniformImagesHaveNoEdges) {
  EdgeWorkspace ws;
  EdgeList out;
  for (const EdgeMethod m : {EdgeMethod::Laplace, EdgeMethod::SobelThinning}) {
    for (const int value : {0, 1, 255}) {
      out.assign(3, EdgePixel{});
      EXPECT_EQ(detectEdges(m, cv::Mat(48, 64, CV_8UC1, cv::Scalar(value)), out, ws), Status::NoEdges) << value;
      EXPECT_TRUE(out.empty());
    }
    EXPECT_EQ(detectEdges(m, cv::Mat(1, 1, CV_8UC1, cv::Scalar(255)), out, ws), Status::NoEdges);
  }
}

// ---------------------------------------------------------------- Laplace

TEST(LaplaceEdges, MatchesDefinitionAndOpenCvSobelOnRandomImages) {
  std::mt19937 rng(20240601);
  EdgeList out;
  for (int i = 0; i < 3000; ++i) {
    const cv::Size size(uniformInt(rng, 1, 90), uniformInt(rng, 1, 70));
    cv::Mat binary = randomBinary(rng, size, uniformInt(rng, 0, 3) == 0 ? uniformInt(rng, 1, 255) : 255);
    if (i % 3 == 0 && size.width > 4 && size.height > 4) {
      // A region of interest: rows are not contiguous in memory.
      binary = binary(cv::Rect(1, 2, size.width - 3, size.height - 4));
    }
    const Status s = detectEdgesLaplace(binary, out);
    const cv::Mat expected = definitionLaplace(binary);
    ASSERT_EQ(s, cv::countNonZero(expected) ? Status::Ok : Status::NoEdges) << "image " << i;
    ASSERT_EQ(cv::countNonZero(maskOf(out, binary.size()) != expected), 0) << "image " << i;
    ASSERT_EQ(out.size(), static_cast<std::size_t>(cv::countNonZero(expected))) << "image " << i;
    ASSERT_TRUE(rasterOrdered(out)) << "image " << i;
    expectGradientsMatchOpenCv(binary, out);
  }
}

// The SSE2 and AVX2 loops (16 and 32 pixels per block) give the same list, pixel for
// pixel and gradient for gradient, and eq. 2.25's: images wide enough for several
// blocks and a ragged tail, and views whose rows are not aligned.
TEST(LaplaceEdges, EveryInstructionSetGivesTheSameEdges) {
  const SimdLevel widest = simdLevel();
  std::mt19937 rng(20261123);
  EdgeList narrow, wide;
  for (int i = 0; i < 600; ++i) {
    const cv::Size size(uniformInt(rng, 1, 220), uniformInt(rng, 1, 40));
    cv::Mat binary = randomBinary(rng, size, 255);
    if (i % 2 == 0 && size.width > 6 && size.height > 4)
      binary = binary(cv::Rect(uniformInt(rng, 1, 5), 1, size.width - 6, size.height - 2));
    setSimdCeiling(SimdLevel::Sse2);
    const Status narrow_status = detectEdgesLaplace(binary, narrow);
    setSimdCeiling(SimdLevel::Avx2);
    const Status wide_status = detectEdgesLaplace(binary, wide);
    ASSERT_EQ(narrow_status, wide_status) << "image " << i;
    const cv::Mat expected = definitionLaplace(binary);
    ASSERT_EQ(narrow.size(), static_cast<std::size_t>(cv::countNonZero(expected))) << "image " << i;
    ASSERT_EQ(cv::countNonZero(maskOf(narrow, binary.size()) != expected), 0) << "image " << i;
    ASSERT_EQ(narrow.size(), wide.size()) << "image " << i;
    for (std::size_t k = 0; k < narrow.size(); ++k) {
      ASSERT_EQ(narrow[k].x, wide[k].x) << "image " << i;
      ASSERT_EQ(narrow[k].y, wide[k].y) << "image " << i;
      ASSERT_EQ(narrow[k].gx, wide[k].gx) << "image " << i;
      ASSERT_EQ(narrow[k].gy, wide[k].gy) << "image " << i;
    }
  }
  setSimdCeiling(SimdLevel::Avx2);
  EXPECT_EQ(simdLevel(), widest);
  if (widest != SimdLevel::Avx2) GTEST_SKIP() << "this processor has no AVX2: only the SSE2 loop was compared";
}

TEST(LaplaceEdges, FilledRectangleGivesItsOutline) {
  cv::Mat binary(60, 80, CV_8UC1, cv::Scalar(0));
  const cv::Rect r(10, 7, 33, 21);
  binary(r).setTo(255);
  EdgeList out;
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  cv::Mat expected(binary.size(), CV_8UC1, cv::Scalar(0));
  cv::rectangle(expected, r, cv::Scalar(255), 1);  // the one-pixel outline inside r
  EXPECT_EQ(cv::countNonZero(maskOf(out, binary.size()) != expected), 0);
  EXPECT_EQ(out.size(), static_cast<std::size_t>(2 * (33 + 21) - 4));
}

// Separated blobs: each contour is one closed 8-connected curve (no end points) of
// white pixels, one pixel thick (every contour pixel touches the background through
// a 4-neighbour) and complete (no interior pixel does).
TEST(LaplaceEdges, OneThinClosedContourPerBlob) {
  std::mt19937 rng(7);
  EdgeList out;
  for (int trial = 0; trial < 200; ++trial) {
    cv::Mat binary(240, 320, CV_8UC1, cv::Scalar(0));
    int blobs = 0;
    for (int cy = 0; cy < 4; ++cy)
      for (int cx = 0; cx < 4; ++cx) {
        if (uniformInt(rng, 0, 3) == 0) continue;
        // Each blob in its own 80x60 cell with a margin, so contours never touch.
        const cv::Point centre(cx * 80 + 40, cy * 60 + 30);
        if (uniformInt(rng, 0, 1)) {
          const cv::Size axes(uniformInt(rng, 4, 27), uniformInt(rng, 4, 27));  // fits rotated
          cv::ellipse(binary, centre, axes, uniformInt(rng, 0, 179), 0, 360, cv::Scalar(255), cv::FILLED);
        } else {
          const cv::Point half(uniformInt(rng, 1, 35), uniformInt(rng, 1, 25));
          cv::rectangle(binary, centre - half, centre + half, cv::Scalar(255), cv::FILLED);
        }
        ++blobs;
      }
    const Status s = detectEdgesLaplace(binary, out);
    ASSERT_EQ(s, blobs ? Status::Ok : Status::NoEdges);
    const cv::Mat mask = maskOf(out, binary.size());
    const cv::Mat interior = (binary != 0) & ~mask;
    ASSERT_EQ(eightComponents(mask), blobs) << "trial " << trial;
    for (const auto& p : out) {
      ASSERT_NE(binary.at<std::uint8_t>(p.y, p.x), 0);
      ASSERT_GE(eightNeighboursInMask(mask, p.x, p.y), 2) << "trial " << trial << " at " << p.x << "," << p.y;
      const bool touchesBlack = binary.at<std::uint8_t>(p.y - 1, p.x) == 0 || binary.at<std::uint8_t>(p.y + 1, p.x) == 0 ||
                                binary.at<std::uint8_t>(p.y, p.x - 1) == 0 || binary.at<std::uint8_t>(p.y, p.x + 1) == 0;
      ASSERT_TRUE(touchesBlack);
    }
    cv::Mat grown;  // the interior grown by its 4-neighbours stays white
    cv::dilate(interior, grown, cv::getStructuringElement(cv::MORPH_CROSS, cv::Size(3, 3)));
    ASSERT_EQ(cv::countNonZero(grown & (binary == 0)), 0) << "trial " << trial;
  }
}

// A one-pixel-wide line is its own edge: edge pixels on the line, none beside it.
TEST(LaplaceEdges, OnePixelWideLinesAreTheirOwnEdges) {
  std::mt19937 rng(11);
  EdgeList out;
  for (int trial = 0; trial < 300; ++trial) {
    cv::Mat binary(50, 70, CV_8UC1, cv::Scalar(0));
    const cv::Point a(uniformInt(rng, 1, 68), uniformInt(rng, 1, 48));
    const cv::Point b(uniformInt(rng, 1, 68), uniformInt(rng, 1, 48));
    cv::line(binary, a, b, cv::Scalar(255), 1, cv::LINE_8);
    const Status s = detectEdgesLaplace(binary, out);
    if (a == b) {  // a single white pixel: itself
      ASSERT_EQ(s, Status::Ok);
    }
    ASSERT_EQ(cv::countNonZero(maskOf(out, binary.size()) != binary), 0) << a << " " << b;
  }
}

TEST(LaplaceEdges, ImageBorderIsNeverAnEdge) {
  // A rectangle touching the left, top and right borders: its outline is open there.
  cv::Mat binary(40, 50, CV_8UC1, cv::Scalar(0));
  binary(cv::Rect(0, 0, 50, 20)).setTo(255);
  EdgeList out;
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  ASSERT_EQ(out.size(), 50u);
  for (const auto& p : out) EXPECT_EQ(p.y, 19);

  // A disk cut by the bottom-right corner: one open contour whose two ends lie on
  // the image border, and no edge pixel along the border between them.
  binary.setTo(0);
  cv::circle(binary, cv::Point(45, 35), 15, cv::Scalar(255), cv::FILLED);
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  const cv::Mat mask = maskOf(out, binary.size());
  EXPECT_EQ(eightComponents(mask), 1);
  int ends = 0;
  for (const auto& p : out) {
    const int n = eightNeighboursInMask(mask, p.x, p.y);
    if (n == 1) {
      ++ends;
      EXPECT_TRUE(p.x == binary.cols - 1 || p.y == binary.rows - 1) << p.x << "," << p.y;
    } else {
      EXPECT_EQ(n, 2) << p.x << "," << p.y;
    }
  }
  EXPECT_EQ(ends, 2);
  EXPECT_EQ(cv::countNonZero(mask.col(binary.cols - 1)), 1);
  EXPECT_EQ(cv::countNonZero(mask.row(binary.rows - 1)), 1);
}

TEST(LaplaceEdges, GradientPointsFromBlackToWhite) {
  EdgeList out;
  cv::Mat binary(20, 30, CV_8UC1, cv::Scalar(0));
  binary.colRange(12, 30).setTo(255);  // white on the right
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  ASSERT_EQ(out.size(), 20u);
  for (const auto& p : out) {
    EXPECT_EQ(p.x, 12);
    EXPECT_EQ(p.gx, 4);
    EXPECT_EQ(p.gy, 0);
  }
  binary = 255 - binary;  // white on the left
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  for (const auto& p : out) {
    EXPECT_EQ(p.x, 11);
    EXPECT_EQ(p.gx, -4);
    EXPECT_EQ(p.gy, 0);
  }
  binary.setTo(0);
  binary.rowRange(9, 20).setTo(255);  // white below (+v)
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  ASSERT_EQ(out.size(), 30u);
  for (const auto& p : out) {
    EXPECT_EQ(p.y, 9);
    EXPECT_EQ(p.gx, 0);
    EXPECT_EQ(p.gy, 4);
  }
  binary = 255 - binary;  // white above
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  for (const auto& p : out) {
    EXPECT_EQ(p.y, 8);
    EXPECT_EQ(p.gx, 0);
    EXPECT_EQ(p.gy, -4);
  }
  // The top-left corner of a white square: the gradient points down-right, inwards.
  binary.setTo(0);
  binary(cv::Rect(10, 5, 8, 8)).setTo(255);
  ASSERT_EQ(detectEdgesLaplace(binary, out), Status::Ok);
  EXPECT_EQ(out.front().x, 10);
  EXPECT_EQ(out.front().y, 5);
  EXPECT_EQ(out.front().gx, 3);
  EXPECT_EQ(out.front().gy, 3);
}

// ---------------------------------------------------------------- Sobel + thinning

bool hasTriple(const cv::Mat& mask) {
  for (int y = 0; y + 1 < mask.rows; ++y)
    for (int x = 0; x + 1 < mask.cols; ++x) {
      const int n = (mask.at<std::uint8_t>(y, x) != 0) + (mask.at<std::uint8_t>(y, x + 1) != 0) +
                    (mask.at<std::uint8_t>(y + 1, x) != 0) + (mask.at<std::uint8_t>(y + 1, x + 1) != 0);
      if (n >= 3) return true;
    }
  return false;
}

// Eq. 2.21: every pixel with a non-zero Sobel gradient.
cv::Mat sobelMagnitudeMask(const cv::Mat& binary) {
  cv::Mat gx, gy;
  openCvSobel(binary, gx, gy);
  return (gx != 0) | (gy != 0);
}

TEST(SobelThinningEdges, ThinSubsetOfSobelEdgesOnRandomImages) {
  std::mt19937 rng(99);
  EdgeWorkspace ws;
  EdgeList out;
  for (int i = 0; i < 1500; ++i) {
    const cv::Size size(uniformInt(rng, 1, 70), uniformInt(rng, 1, 60));
    const cv::Mat binary = randomBinary(rng, size);
    const Status s = detectEdgesSobelThinning(binary, out, ws);
    const cv::Mat sobel = sobelMagnitudeMask(binary);
    const cv::Mat mask = maskOf(out, size);
    ASSERT_EQ(s, out.empty() ? Status::NoEdges : Status::Ok);
    ASSERT_EQ(s == Status::NoEdges, cv::countNonZero(sobel) == 0) << "image " << i;
    ASSERT_EQ(cv::countNonZero(mask & ~sobel), 0) << "image " << i;  // only deletes
    ASSERT_FALSE(hasTriple(mask)) << "image " << i;                   // no three pairwise neighbours
    ASSERT_TRUE(rasterOrdered(out));
    expectGradientsMatchOpenCv(binary, out);
  }
}

// Eq. 2.21 marks both sides of a straight step; thinning keeps the white side, where
// the Laplace edge lies.
TEST(SobelThinningEdges, ThinsAStraightStepToItsWhiteSide) {
  EdgeWorkspace ws;
  EdgeList thinned, laplace;
  cv::Mat binary(30, 40, CV_8UC1, cv::Scalar(0));
  binary.colRange(20, 40).setTo(255);
  for (int variant = 0; variant < 4; ++variant) {
    const cv::Mat b = variant % 2 ? 255 - binary : binary;
    const cv::Mat image = variant / 2 ? cv::Mat(b.t()) : b;
    ASSERT_EQ(cv::countNonZero(sobelMagnitudeMask(image)), 2 * 30) << variant;
    ASSERT_EQ(detectEdgesSobelThinning(image, thinned, ws), Status::Ok);
    ASSERT_EQ(detectEdgesLaplace(image, laplace), Status::Ok);
    ASSERT_EQ(thinned.size(), 30u) << variant;
    for (std::size_t i = 0; i < thinned.size(); ++i) {
      EXPECT_EQ(thinned[i].x, laplace[i].x) << variant;
      EXPECT_EQ(thinned[i].y, laplace[i].y) << variant;
      EXPECT_EQ(thinned[i].gx, laplace[i].gx) << variant;
      EXPECT_EQ(thinned[i].gy, laplace[i].gy) << variant;
    }
  }
}

}  // namespace
}  // namespace imagepro
