#include "core/calibration/pattern.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

TEST(PatternGeometry, GridIsCentredOnTheTargetWithTheSheetAround) {
  const PatternGeometry p;  // 61 x 49 spots, 25 mm apart
  EXPECT_EQ(patternNodeMm(p, 30, 24), Eigen::Vector2d(0.0, 0.0));
  EXPECT_EQ(patternNodeMm(p, 0, 0), Eigen::Vector2d(-750.0, -600.0));
  EXPECT_EQ(patternNodeMm(p, 60, 48), Eigen::Vector2d(750.0, 600.0));
  EXPECT_EQ(patternSheetSizeMm(p), Eigen::Vector2d(1525.0, 1225.0));

  PatternGeometry even = p;
  even.columns = 4;
  even.rows = 2;
  EXPECT_EQ(patternNodeMm(even, 0, 0), Eigen::Vector2d(-37.5, -12.5));
  EXPECT_EQ(patternNodeMm(even, 3, 1), Eigen::Vector2d(37.5, 12.5));
}

TEST(PatternGeometry, DefaultPatternLeavesOutTheFiveByFiveNodesOnTheCard) {
  const PatternGeometry p;
  const TargetGeometry t;
  std::vector<PatternSpot> spots;
  patternSpots(p, t, spots);
  // Card half side 65 mm, spot radius 4 mm: nodes at 0, +-25, +-50 mm touch it, +-75 mm do not.
  EXPECT_EQ(spots.size(), static_cast<size_t>(61 * 49 - 25));
  std::set<std::pair<int, int>> kept;
  for (const PatternSpot& s : spots) {
    kept.insert({s.column, s.row});
    EXPECT_EQ(s.position_mm, patternNodeMm(p, s.column, s.row));
  }
  for (int c = 28; c <= 32; ++c)
    for (int r = 22; r <= 26; ++r) EXPECT_EQ(kept.count({c, r}), 0u) << c << "," << r;
  EXPECT_EQ(kept.count({27, 24}), 1u);
  EXPECT_EQ(kept.count({27, 21}), 1u);  // the corner node (-75, -75)
}

TEST(PatternGeometry, ASpotThatWouldTouchTheCardIsLeftOut) {
  const TargetGeometry t;
  PatternGeometry p;
  p.columns = 7;
  p.rows = 1;
  p.spot_radius_mm = 4.0;
  // Node 3 spacings out at 69 mm: its edge reaches the card's edge at 65 mm exactly.
  p.spot_spacing_mm = 23.0;
  EXPECT_TRUE(patternSpotTouchesCard(p, t, 6, 0));
  p.spot_spacing_mm = 23.5;  // 70.5 mm: 1.5 mm clear of the card
  EXPECT_FALSE(patternSpotTouchesCard(p, t, 6, 0));
  // Diagonal: the distance to the card's corner counts, not to its sides' lines.
  p.columns = 7;
  p.rows = 7;
  p.spot_spacing_mm = 23.0;  // node (69, 69): 5.66 mm from the corner (65, 65)
  EXPECT_FALSE(patternSpotTouchesCard(p, t, 6, 6));
}

// The renderer draws exactly the spots of the list: seen frontally in binary, a kept spot's
// centre is black, and where a left-out spot would reach beyond the card it is white.
TEST(PatternGeometry, SpotListIsWhatTheRendererDraws) {
  const TargetGeometry t;
  PatternGeometry p;
  p.columns = 9;
  p.rows = 9;
  p.spot_spacing_mm = 23.0;  // the ring at +-69 mm touches the card and is left out
  CameraModel cam;
  VirtualSceneOptions scene;
  scene.mode = RenderMode::Binary;
  const Pose frontal{0, 0, 0, 0, 0, 400.0};  // 2 px per mm
  cv::Mat img;
  renderPattern(cam, t, p, scene, frontal, img);
  std::vector<PatternSpot> spots;
  patternSpots(p, t, spots);
  auto pixel = [&](double x, double y) {
    const Eigen::Vector2d uv = projectIdeal(cam, Eigen::Vector3d(x, y, frontal.tz_mm));
    return img.at<unsigned char>(static_cast<int>(std::lround(uv.y())), static_cast<int>(std::lround(uv.x())));
  };
  std::set<std::pair<int, int>> kept;
  for (const PatternSpot& s : spots) {
    kept.insert({s.column, s.row});
    EXPECT_EQ(pixel(s.position_mm.x(), s.position_mm.y()), 0) << s.column << "," << s.row;
  }
  int leftOut = 0;
  for (int c = 0; c < p.columns; ++c)
    for (int r = 0; r < p.rows; ++r) {
      if (kept.count({c, r})) continue;
      ++leftOut;
      const Eigen::Vector2d n = patternNodeMm(p, c, r);
      if (std::abs(n.x()) < 68.0 && std::abs(n.y()) < 68.0) continue;  // on the card
      // 3 mm outwards from the node: beyond the card, inside the spot it would have had.
      const Eigen::Vector2d out = n + 3.0 * n.normalized();
      if (std::abs(out.x()) > 65.0 || std::abs(out.y()) > 65.0) {
        EXPECT_EQ(pixel(out.x(), out.y()), 255) << c << "," << r;
      }
    }
  // Nodes within +-3 spacings (0, +-23, +-46 and the +-69 ring), but for the ring's corners.
  EXPECT_EQ(leftOut, 7 * 7 - 4);
  EXPECT_EQ(kept.count({7, 7}), 1u);
}

}  // namespace
}  // namespace imagepro
