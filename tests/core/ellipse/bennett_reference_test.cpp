// Bennett's accumulator and peak measures against a straightforward restatement of the
// method on real paths (the synthetic library, binary and grey with blur and noise, and
// cluttered target scenes): every pair of sampled pixels walks its ray one cell at a
// time with a box test per cell, the rings about the peak take lround(sqrt) per cell.
// The vector loops (SSE2 and AVX2) must give the same count in every cell and the same
// score, quality, half-score radius and symmetry, to the bit.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/common/simd_level.h"
#include "core/ellipse/bennett.h"
#include "core/ellipse/synthetic_library.h"
#include "core/source/virtual_renderer.h"
#include "scenes.h"

namespace imagepro {
namespace {

constexpr int kMargin = 2;  // bennett.cpp: cells around the path's bounding box

struct RefBox {
  int x0, y0, w, h;
  bool contains(std::int64_t x, std::int64_t y) const { return x >= 0 && y >= 0 && x < w && y < h; }
};

RefBox boxOf(std::span<const EdgePixel> path) {
  int minx = path[0].x, maxx = minx, miny = path[0].y, maxy = miny;
  for (const EdgePixel& p : path) {
    minx = std::min<int>(minx, p.x);
    maxx = std::max<int>(maxx, p.x);
    miny = std::min<int>(miny, p.y);
    maxy = std::max<int>(maxy, p.y);
  }
  return {minx - kMargin, miny - kMargin, maxx - minx + 1 + 2 * kMargin, maxy - miny + 1 + 2 * kMargin};
}

// Every pair of the sampled pixels votes along its ray: from the chord's midpoint M away
// from the tangents' intersection T, in steps of one cell along the dominant axis, in
// 16.16 fixed point from M + half a cell, up to where the ray leaves the box (cell-centre
// coordinates widened by half a cell); each step's cell is counted when it is in the box.
std::vector<std::uint32_t> referenceAccumulator(std::span<const EdgePixel> path, std::span<const std::uint32_t> sample,
                                                const RefBox& box) {
  std::vector<std::uint32_t> acc(static_cast<std::size_t>(box.w) * box.h, 0u);
  for (std::size_t i = 0; i < sample.size(); ++i) {
    for (std::size_t j = i + 1; j < sample.size(); ++j) {
      const EdgePixel& a = path[sample[i]];
      const EdgePixel& b = path[sample[j]];
      const double x1 = a.x - box.x0, y1 = a.y - box.y0, x2 = b.x - box.x0, y2 = b.y - box.y0;
      const double g1x = a.gx, g1y = a.gy, g2x = b.gx, g2y = b.gy;
      const double dx = x2 - x1, dy = y2 - y1;
      if (!((g1x * dx + g1y * dy) * -(g2x * dx + g2y * dy) > 0.0)) continue;  // gradients to one side
      const double mx = 0.5 * (x1 + x2), my = 0.5 * (y1 + y2);
      const double det = g1x * g2y - g1y * g2x;
      if (det == 0.0) {  // parallel tangents: the centre is M
        const std::int64_t cx = std::llround(mx), cy = std::llround(my);
        if (box.contains(cx, cy)) ++acc[static_cast<std::size_t>(cy * box.w + cx)];
        continue;
      }
      const double c1 = g1x * x1 + g1y * y1, c2 = g2x * x2 + g2y * y2;
      const double tx = (c1 * g2y - c2 * g1y) / det, ty = (g1x * c2 - g2x * c1) / det;
      double ux = mx - tx, uy = my - ty;
      const double len2 = ux * ux + uy * uy;
      if (!(len2 > 1e-18)) continue;
      const double inv = 1.0 / std::sqrt(len2);
      ux *= inv;
      uy *= inv;
      const double lo = -0.5, hi_x = box.w - 0.5, hi_y = box.h - 0.5;
      if (mx < lo || mx > hi_x || my < lo || my > hi_y) continue;
      double tmax = std::numeric_limits<double>::infinity();
      if (ux > 0) tmax = std::min(tmax, (hi_x - mx) / ux);
      if (ux < 0) tmax = std::min(tmax, (lo - mx) / ux);
      if (uy > 0) tmax = std::min(tmax, (hi_y - my) / uy);
      if (uy < 0) tmax = std::min(tmax, (lo - my) / uy);
      const double step = 1.0 / std::max(std::abs(ux), std::abs(uy));
      const int steps = static_cast<int>(tmax / step);
      const std::int64_t x = static_cast<std::int64_t>((mx + 0.5) * 65536.0);
      const std::int64_t y = static_cast<std::int64_t>((my + 0.5) * 65536.0);
      const std::int64_t sx = std::llround(ux * step * 65536.0), sy = std::llround(uy * step * 65536.0);
      for (int k = 0; k <= steps; ++k) {
        const std::int64_t cx = (x + k * sx) >> 16, cy = (y + k * sy) >> 16;
        if (box.contains(cx, cy)) ++acc[static_cast<std::size_t>(cy * box.w + cx)];
      }
    }
  }
  return acc;
}

struct RefMeasures {
  double score = 0, half_radius = 0, quality = 0, symmetry = 0, border_distance = 0, cx = 0, cy = 0;
};

// The peak (first cell of the largest count), the centre of symmetry (the box's centre
// when the peak is within two cells of it), the half-score radius over the rings inside
// the box and the radius where a ring's asymmetry first exceeds 0.25, ring r holding the
// cells at lround(distance) = r, cells outside the box counting as empty.
RefMeasures referenceMeasures(const std::vector<std::uint32_t>& acc, const RefBox& box, double weight) {
  RefMeasures m;
  const std::size_t best = static_cast<std::size_t>(std::max_element(acc.begin(), acc.end()) - acc.begin());
  const int px = static_cast<int>(best % box.w), py = static_cast<int>(best / box.w);
  const double peak = acc[best];
  m.score = weight * peak;
  int twice_cx = 2 * px, twice_cy = 2 * py;
  if (std::abs(2 * px - (box.w - 1)) <= 4 && std::abs(2 * py - (box.h - 1)) <= 4) {
    twice_cx = box.w - 1;
    twice_cy = box.h - 1;
  }
  m.cx = box.x0 + 0.5 * twice_cx;
  m.cy = box.y0 + 0.5 * twice_cy;
  auto at = [&](int x, int y) -> double {
    return box.contains(x, y) ? acc[static_cast<std::size_t>(y) * box.w + x] : 0.0;
  };
  const int border = std::min({px, py, box.w - 1 - px, box.h - 1 - py});
  const int reach = std::max({px, py, box.w - 1 - px, box.h - 1 - py});
  m.border_distance = reach;
  std::vector<double> sum(reach + 1), count(reach + 1), diff(reach + 1), both(reach + 1);
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const int r = static_cast<int>(std::lround(std::sqrt(static_cast<double>(dx * dx + dy * dy))));
      if (r > reach) continue;
      const double u = at(px + dx, py + dy), v = at(twice_cx - px - dx, twice_cy - py - dy);
      if (r <= border) {
        sum[r] += u;
        count[r] += 1.0;
      }
      diff[r] += std::abs(u - v);
      both[r] += u + v;
    }
  }
  m.half_radius = border;
  double prev = peak;
  for (int r = 1; r <= border; ++r) {
    const double mean = sum[r] / count[r];
    if (mean <= 0.5 * peak) {
      m.half_radius = (r - 1) + (prev - 0.5 * peak) / (prev - mean);
      break;
    }
    prev = mean;
  }
  m.quality = m.score / std::sqrt(std::max(m.half_radius, 0.25));
  m.symmetry = reach + 1;
  for (int r = 1; r <= reach; ++r) {
    if (both[r] > 0.0 && diff[r] / both[r] > 0.25) {
      m.symmetry = r;
      break;
    }
  }
  return m;
}

class SimdCeiling {
 public:
  explicit SimdCeiling(SimdLevel level) { setSimdCeiling(level); }
  ~SimdCeiling() { setSimdCeiling(SimdLevel::Avx2); }
};

// Checks every path of at least 20 pixels of `paths` on both vector widths, all pixels
// and (for longer paths) a sample of max_points; returns the paths checked.
int checkPaths(const Paths& paths) {
  int checked = 0;
  BennettWorkspace ws;
  for (std::size_t k = 0; k < paths.pathCount(); ++k) {
    const auto path = paths.path(k);
    if (path.size() < 20) continue;
    for (const int max_points : {0, 96}) {
      if (max_points > 0 && path.size() <= static_cast<std::size_t>(max_points)) continue;
      std::vector<std::uint32_t> first_counts;
      BennettResult first;
      for (const SimdLevel level : {SimdLevel::Avx2, SimdLevel::Sse2}) {
        SCOPED_TRACE(::testing::Message() << "path " << k << " (" << path.size() << " px), max_points " << max_points
                                          << (level == SimdLevel::Sse2 ? ", SSE2" : ", widest"));
        const SimdCeiling ceiling(level);
        BennettResult r;
        const Status st = bennettAccumulate(path, max_points, ws, r);
        if (st != Status::Ok) {
          EXPECT_EQ(st, Status::NoTarget);
          continue;
        }
        const RefBox box = boxOf(path);
        const std::vector<std::uint32_t> want = referenceAccumulator(path, ws.sample, box);
        EXPECT_EQ(ws.accumulator.size(), want.size());
        if (ws.accumulator.size() != want.size()) continue;
        std::size_t differing = 0;
        for (std::size_t c = 0; c < want.size(); ++c) differing += ws.accumulator[c] != want[c];
        EXPECT_EQ(differing, 0u);
        const double usable = static_cast<double>(std::count_if(
            path.begin(), path.end(), [](const EdgePixel& p) { return p.gx != 0 || p.gy != 0; }));
        const double m = static_cast<double>(ws.sample.size());
        const RefMeasures ref = referenceMeasures(want, box, (usable * (usable - 1)) / (m * (m - 1)));
        EXPECT_EQ(r.score, ref.score);
        EXPECT_EQ(r.half_radius_px, ref.half_radius);
        EXPECT_EQ(r.quality, ref.quality);
        EXPECT_EQ(r.symmetry_px, ref.symmetry);
        EXPECT_EQ(r.border_distance_px, ref.border_distance);
        EXPECT_EQ(r.cx, ref.cx);
        EXPECT_EQ(r.cy, ref.cy);
        if (level == SimdLevel::Avx2) {
          first = r;
          first_counts = ws.accumulator;
        } else {
          EXPECT_EQ(ws.accumulator, first_counts);
          EXPECT_EQ(r.pairs, first.pairs);
          EXPECT_EQ(r.peak_fraction, first.peak_fraction);
        }
        ++checked;
      }
    }
  }
  return checked;
}

TEST(BennettReference, LibraryPathsCellByCell) {
  test::PathPipeline p;
  int checked = 0, images = 0;
  const auto library = syntheticLibrary();
  // Every ninth shape (rectangles and ellipses, all sizes and aspects), binary and grey.
  for (std::size_t i = 0; i < library.size(); i += 9, ++images) {
    cv::Mat img;
    renderLibraryImage(library[i], img);
    ASSERT_EQ(p.run(img, 128), Status::Ok);
    checked += checkPaths(p.paths);
    LibraryGreyOptions grey;
    grey.blur_sigma_px = 1.5;
    grey.noise_sigma = 8.0;
    renderLibraryImageGrey(library[i], grey, img);
    ASSERT_EQ(p.run(img, 125), Status::Ok);
    checked += checkPaths(p.paths);
  }
  EXPECT_GE(checked, 2 * 2 * images);
}

TEST(BennettReference, ClutteredScenePathsCellByCell) {
  test::PathPipeline p;
  int checked = 0;
  const Pose poses[] = {{20, -15, 30, 120, -60, 900}, {-5, 20, -30, 20, 10, 450}};
  for (int i = 0; i < 2; ++i) {
    VirtualSceneOptions scene;
    scene.mode = RenderMode::Grey;
    scene.clutter = 12 + 10 * i;
    scene.seed = 40 + static_cast<unsigned>(i);
    scene.noise_sigma = 4.0;
    scene.blur_sigma_px = 0.8;
    cv::Mat grey;
    renderTarget(CameraModel{}, TargetGeometry{}, scene, poses[i], grey, static_cast<std::uint64_t>(i));
    ASSERT_EQ(p.run(grey), Status::Ok);
    checked += checkPaths(p.paths);
  }
  EXPECT_GE(checked, 20);
}

}  // namespace
}  // namespace imagepro
