// The vector passes over a path's pixels give exactly the 64-bit integer sums, on
// either width and across the limits of their int32 blocks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/common/simd_level.h"
#include "core/ellipse/direct_fit.h"
#include "core/ellipse/ellipse_trace.h"
#include "core/ellipse/pixel_passes.h"

namespace imagepro {
namespace {

pixel_passes::PathSums scalarSums(std::span<const EdgePixel> path, int ox, int oy) {
  pixel_passes::PathSums s;
  s.bounds = {path[0].x, path[0].x, path[0].y, path[0].y};
  for (const EdgePixel& p : path) pixel_passes::detail::addScalar(p, ox, oy, s);
  return s;
}

void expectSame(const pixel_passes::PathSums& a, const pixel_passes::PathSums& b) {
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.xx_yy, b.xx_yy);
  EXPECT_EQ(a.gx, b.gx);
  EXPECT_EQ(a.gy, b.gy);
  EXPECT_EQ(a.g_dot, b.g_dot);
  EXPECT_EQ(a.bounds.min_x, b.bounds.min_x);
  EXPECT_EQ(a.bounds.max_x, b.bounds.max_x);
  EXPECT_EQ(a.bounds.min_y, b.bounds.min_y);
  EXPECT_EQ(a.bounds.max_y, b.bounds.max_y);
}

TEST(PixelPasses, PathSumsAreTheExactIntegerSums) {
  std::mt19937 rng(7);
  // Spreads within one block's reach, beyond it (64-bit fallback), and beyond int16
  // differences; gradients of the Sobel range and far larger ones.
  for (const int spread : {3, 600, 1023, 1024, 5000, 30000}) {
    for (const int grad : {4, 1023, 2000}) {
      for (const std::size_t n : {1u, 2u, 3u, 5u, 8u, 1023u, 1024u, 1027u, 3001u}) {
        SCOPED_TRACE(::testing::Message() << spread << " " << grad << " " << n);
        std::uniform_int_distribution<int> pos(-spread, spread), g(-grad, grad);
        std::vector<EdgePixel> path(n);
        for (EdgePixel& p : path)
          p = {static_cast<std::int16_t>(std::clamp(2000 + pos(rng), -32768, 32767)),
               static_cast<std::int16_t>(std::clamp(-1000 + pos(rng), -32768, 32767)),
               static_cast<std::int16_t>(g(rng)), static_cast<std::int16_t>(g(rng))};
        const int ox = path[0].x, oy = path[0].y;
        const pixel_passes::PathSums want = scalarSums(path, ox, oy);
        expectSame(pixel_passes::pathSums(path, ox, oy), want);
#if defined(__SSE2__)
        pixel_passes::PathSums s;
        s.bounds = {path[0].x, path[0].x, path[0].y, path[0].y};
        pixel_passes::detail::sse2::sums(path, ox, oy, s);
        expectSame(s, want);
#endif
      }
    }
  }
}

TEST(PixelPasses, ConicMomentsOfPixelsAreExact) {
  // The vector moment sums (two pixels per AVX2 vector, or one per SSE2 vector) against
  // the point-by-point sums, which are exact here: every sum is an integer below 2^53.
  std::mt19937 rng(11);
  for (const int spread : {2, 100, 600}) {
    for (const std::size_t n : {6u, 7u, 64u, 1001u, 3000u}) {
      SCOPED_TRACE(::testing::Message() << spread << " " << n);
      std::uniform_int_distribution<int> pos(-spread, spread);
      std::vector<EdgePixel> path(n);
      for (EdgePixel& p : path)
        p = {static_cast<std::int16_t>(320 + pos(rng)), static_cast<std::int16_t>(240 + pos(rng)), 1, -1};
      ConicMoments point_sums;
      for (const EdgePixel& p : path) point_sums.add(p.x, p.y);
      for (const SimdLevel level : {SimdLevel::Sse2, SimdLevel::Avx2}) {
        setSimdCeiling(level);
        ConicMoments vector_sums;
        vector_sums.add(path);
        EXPECT_EQ(vector_sums.count, point_sums.count);
        for (std::size_t k = 0; k < vector_sums.sum.size(); ++k)
          EXPECT_EQ(vector_sums.sum[k], point_sums.sum[k]) << k << " at level " << static_cast<int>(level);
        // The path summary's sums likewise, on whichever width the ceiling leaves.
        expectSame(pixel_passes::pathSums(path, path[0].x, path[0].y), scalarSums(path, path[0].x, path[0].y));
      }
      setSimdCeiling(SimdLevel::Avx2);
    }
  }
}

// The contour trace takes two points at a time with SSE2 and four with AVX: the same
// inliers, traced share and mean Sampson distance to the bit, on whole, partial, noisy,
// border-cut and wrong-size ellipses.
TEST(PixelPasses, EveryInstructionSetTracesTheSameArcs) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    SCOPED_TRACE(i);
    const Ellipse e{40.0 + 560.0 * u(rng), 40.0 + 400.0 * u(rng), 8.0 + 150.0 * u(rng), 0.0, 180.0 * u(rng)};
    Ellipse truth = e;
    truth.b = truth.a * (0.2 + 0.8 * u(rng));
    const double from = 360.0 * u(rng), span = 30.0 + 330.0 * u(rng), noise = 2.0 * u(rng);
    std::vector<EdgePixel> path;
    std::normal_distribution<double> gauss(0.0, noise);
    const int n = 6 + static_cast<int>(400.0 * u(rng));
    const double th = truth.angle_deg * std::numbers::pi / 180.0;
    for (int k = 0; k < n; ++k) {
      const double s = (from + span * k / n) * std::numbers::pi / 180.0;
      const double x = truth.a * std::cos(s), y = truth.b * std::sin(s);
      path.push_back({static_cast<std::int16_t>(std::lround(truth.cx + x * std::cos(th) - y * std::sin(th) + gauss(rng))),
                      static_cast<std::int16_t>(std::lround(truth.cy + x * std::sin(th) + y * std::cos(th) + gauss(rng))),
                      1, 1});
    }
    ConicMoments m;
    m.add(path);
    EllipseFit fit;
    if (!ok(fitEllipse(m, fit))) continue;
    for (const cv::Size image : {cv::Size(), cv::Size(640, 480)}) {
      EllipseTrace narrow, wide;
      setSimdCeiling(SimdLevel::Sse2);
      traceEllipse(fit, path, 1.0, image, narrow);
      setSimdCeiling(SimdLevel::Avx2);
      traceEllipse(fit, path, 1.0, image, wide);
      EXPECT_EQ(narrow.mean_sampson_px, wide.mean_sampson_px);
      EXPECT_EQ(narrow.traced, wide.traced);
      EXPECT_EQ(narrow.observable, wide.observable);
      EXPECT_EQ(narrow.inliers, wide.inliers);
    }
  }
}

}  // namespace
}  // namespace imagepro
