// Target selection on rendered frames: the white disk with two spots among distractors,
// two targets, occluders and the image border.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "core/ellipse/detect.h"
#include "core/source/virtual_renderer.h"
#include "scenes.h"
#include "support/plain_scene.h"

namespace imagepro {
namespace {

constexpr double kPi = 3.14159265358979323846;

class TargetScene : public ::testing::Test {
 protected:
  TargetScene() {
    scene.noise_sigma = 3.0;
    scene.blur_sigma_px = 0.7;
  }
  // Threshold at mid-grey, so that the binary boundary is the disk's true boundary.
  Status detect(const cv::Mat& grey) {
    const Status st = pipe.run(grey, (scene.white_level + scene.black_level) / 2);
    if (!ok(st)) return st;
    return detectTarget(options, target, pipe.paths, grey.size(), ws, found);
  }
  cv::Mat render(const Pose& pose) {
    cv::Mat img;
    renderTarget(camera, target, scene, pose, img, 1);
    return img;
  }
  void expectEllipseOfPose(const TargetDetection& d, const Pose& pose, double tol_px = 0.6) {
    const Ellipse truth = test::diskImage(camera, target, pose);
    EXPECT_NEAR(d.ellipse.cx, truth.cx, tol_px);
    EXPECT_NEAR(d.ellipse.cy, truth.cy, tol_px);
    // The edge pixels are the white pixels just inside the disk's boundary.
    EXPECT_NEAR(d.ellipse.a, truth.a - 0.5, tol_px);
    EXPECT_NEAR(d.ellipse.b, truth.b - 0.5, tol_px);
    if (truth.a - truth.b > 2.0) {
      EXPECT_NEAR(test::angleDiffDeg(d.ellipse.angle_deg, truth.angle_deg), 0.0, 2.0);
    }
  }
  // A white disk without spots on its own black card: the target's look-alike.
  void drawPlainDisk(cv::Mat& img, cv::Point centre, int radius) {
    cv::rectangle(img, cv::Rect(centre.x - radius - 15, centre.y - radius - 15, 2 * radius + 30, 2 * radius + 30),
                  cv::Scalar(scene.black_level), cv::FILLED);
    cv::circle(img, centre, radius, cv::Scalar(scene.white_level), cv::FILLED, cv::LINE_AA);
  }

  // Pastes the card of a target rendered at `pose` (its projected corners' box) into img.
  void pasteCard(cv::Mat& img, const Pose& pose) {
    const cv::Mat other = render(pose);
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    const Eigen::Matrix3d R = rotationMatrix(pose);
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0}) {
        const Eigen::Vector2d p = projectIdeal(camera, R * Eigen::Vector3d(sx * 65, sy * 65, 0) + translation(pose));
        x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
      }
    const cv::Rect box = cv::Rect(cv::Point(int(x0) - 1, int(y0) - 1), cv::Point(int(x1) + 2, int(y1) + 2)) &
                         cv::Rect(0, 0, img.cols, img.rows);
    other(box).copyTo(img(box));
  }

  CameraModel camera;
  TargetGeometry target;
  VirtualSceneOptions scene = test::plainScene();
  EllipseOptions options;
  test::PathPipeline pipe;
  EllipseWorkspace ws;
  std::vector<TargetDetection> found;
};

TEST_F(TargetScene, FoundWithItsSpotsAcrossPoses) {
  for (const Pose pose : {Pose{0, 0, 0, 0, 0, 800}, Pose{40, 30, 20, 30, -20, 800}, Pose{60, 0, 90, -80, 40, 600},
                          Pose{0, 55, -30, 0, 0, 1500}, Pose{20, -20, 0, 100, 80, 3000}}) {
    SCOPED_TRACE(::testing::Message() << pose.rx_deg << " " << pose.ry_deg << " " << pose.tz_mm);
    ASSERT_EQ(detect(render(pose)), Status::Ok);
    ASSERT_EQ(found.size(), 1u);
    const TargetDetection& d = found[0];
    EXPECT_TRUE(d.spots_found);
    EXPECT_FALSE(d.robust);
    expectEllipseOfPose(d, pose);
    // The centre spot lies near the projected disk centre.
    const Eigen::Vector2d centre = projectIdeal(camera, translation(pose));
    const PathSummary& spot = ws.paths[d.spot_paths[0]];
    EXPECT_NEAR(spot.cx, centre.x(), 1.0);
    EXPECT_NEAR(spot.cy, centre.y(), 1.0);
    EXPECT_LT(d.fit_error, options.max_relative_error);
    EXPECT_GT(d.traced, 0.95);
    EXPECT_EQ(ws.consensus_fits, 0u);  // the common frame fits one path, once
  }
}

TEST_F(TargetScene, PlainDiskAndClutterAreNotTheTarget) {
  scene.clutter = 25;
  const Pose pose{30, -20, 10, 60, 40, 900};
  cv::Mat img = render(pose);
  drawPlainDisk(img, {110, 110}, 50);  // larger and rounder than the target
  cv::rectangle(img, cv::Rect(480, 330, 120, 60), cv::Scalar(scene.white_level), cv::FILLED);
  ASSERT_EQ(detect(img), Status::Ok);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].spots_found);
  EXPECT_EQ(ws.consensus_fits, 0u);
  expectEllipseOfPose(found[0], pose);
  // Both the disk and the target are ellipses to the shape-only classification.
  std::vector<TargetDetection> shapes;
  ASSERT_EQ(detectEllipses(options, pipe.paths, img.size(), ws, shapes), Status::Ok);
  bool disk_seen = false;
  for (const auto& s : shapes) disk_seen |= std::hypot(s.ellipse.cx - 110, s.ellipse.cy - 110) < 1.0;
  EXPECT_TRUE(disk_seen);
}

TEST_F(TargetScene, WithoutTheTargetThePlainDiskIsOnlyAFallback) {
  cv::Mat img(480, 640, CV_8UC1, cv::Scalar(scene.background_level));
  drawPlainDisk(img, {320, 240}, 60);
  ASSERT_EQ(detect(img), Status::Ok);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_FALSE(found[0].spots_found);
  EXPECT_EQ(found[0].spot_paths[0], kNoPath);
  EXPECT_NEAR(found[0].ellipse.cx, 320.0, 0.5);
  options.require_target_spots = true;
  EXPECT_EQ(detect(img), Status::NoTarget);
}

TEST_F(TargetScene, TwoTargetsAreAmbiguousOrBothReported) {
  const Pose left{0, 20, 0, -150, 0, 800}, right{10, -30, 45, 150, 20, 800};
  cv::Mat img = render(left);
  pasteCard(img, right);
  EXPECT_EQ(detect(img), Status::AmbiguousTarget);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(ws.consensus_fits, 0u);  // both pass the plain fit
  options.report_all_targets = true;
  ASSERT_EQ(detect(img), Status::Ok);
  ASSERT_EQ(found.size(), 2u);
  const bool left_first = found[0].ellipse.cx < found[1].ellipse.cx;
  expectEllipseOfPose(found[left_first ? 0 : 1], left);
  expectEllipseOfPose(found[left_first ? 1 : 0], right);
}

// Share of the perimeter of `e` above the line v = y_chord (smaller v), by arc length.
double shareAbove(const Ellipse& e, double y_chord) {
  const double th = e.angle_deg * kPi / 180.0;
  auto at = [&](double t) {
    const double u = e.a * std::cos(t), v = e.b * std::sin(t);
    return Eigen::Vector2d(e.cx + u * std::cos(th) - v * std::sin(th), e.cy + u * std::sin(th) + v * std::cos(th));
  };
  double above = 0.0, total = 0.0;
  Eigen::Vector2d prev = at(0.0);
  for (int k = 1; k <= 7200; ++k) {
    const Eigen::Vector2d p = at(2.0 * kPi * k / 7200);
    const double len = (p - prev).norm();
    total += len;
    if (0.5 * (p.y() + prev.y()) < y_chord) above += len;
    prev = p;
  }
  return above / total;
}

// The chord v = y below which the cap above it holds `share` of the perimeter of `e`.
double chordForShare(const Ellipse& e, double share) {
  double lo = e.cy - e.a - e.b, hi = e.cy + e.a + e.b;  // shareAbove(lo) = 0, shareAbove(hi) = 1
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (shareAbove(e, mid) < share ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Covers everything above the chord v = y_chord within the ellipse's reach (a black cap).
void occludeAbove(cv::Mat& img, const Ellipse& e, double y_chord, int level) {
  const double reach = e.a + 20;
  const cv::Point2d corners[4] = {{e.cx - reach, y_chord}, {e.cx + reach, y_chord}, {e.cx + reach, e.cy - reach},
                                  {e.cx - reach, e.cy - reach}};
  // Sub-pixel corners (8 fractional bits), so the chord sits where the share puts it.
  std::vector<cv::Point> poly;
  for (const cv::Point2d& c : corners) poly.emplace_back(int(std::lround(c.x * 256)), int(std::lround(c.y * 256)));
  cv::fillConvexPoly(img, poly, cv::Scalar(level), cv::LINE_8, 8);
}

// Covers the cap of the disk image holding `share` of its contour (measured along the
// exact ellipse of the pose).
void occludeCap(cv::Mat& img, const Ellipse& e, double share, int level) {
  occludeAbove(img, e, chordForShare(e, share), level);
}

TEST_F(TargetScene, OccludedTargetFoundByConsensusFit) {
  const Pose pose{0, 25, 0, 0, 0, 700};
  const Ellipse truth = test::diskImage(camera, target, pose);
  // Of the contour hidden, up to the limit: a target with at least 75 % of its
  // contour visible is found.
  for (const double share : {0.12, 0.2, 0.24, 0.245, 0.25}) {
    SCOPED_TRACE(share);
    cv::Mat img = render(pose);
    occludeCap(img, truth, share, scene.black_level);
    ASSERT_EQ(detect(img), Status::Ok);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_TRUE(found[0].robust);
    EXPECT_TRUE(found[0].spots_found);
    expectEllipseOfPose(found[0], pose, 1.0);
    EXPECT_GE(found[0].traced, options.robust_min_traced_fraction);
    EXPECT_LT(found[0].traced, 1.0 - share + 0.05);
  }
  // Without the consensus fit the straight part spoils the plain fit (thesis fig. 2.28).
  cv::Mat img = render(pose);
  occludeCap(img, truth, 0.2, scene.black_level);
  options.robust_fit = false;
  options.require_target_spots = true;
  EXPECT_EQ(detect(img), Status::NoTarget);
}

// More than a quarter hidden: the path's consensus fit gives up, and the rim is taken from
// the spots (both whole) as long as over 60 % of it is seen; with less it is no target.
TEST_F(TargetScene, MoreThanAQuarterOccludedIsFoundFromTheSpotsUpToTwoFifths) {
  const Pose pose{0, 25, 0, 0, 0, 700};
  const Ellipse truth = test::diskImage(camera, target, pose);
  cv::Mat img = render(pose);
  occludeCap(img, truth, 0.35, scene.black_level);
  ASSERT_EQ(detect(img), Status::Ok);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].robust);
  expectEllipseOfPose(found[0], pose, 1.0);
  EXPECT_GE(found[0].traced, 0.6);
  EXPECT_LT(found[0].traced, 0.7);
  img = render(pose);
  occludeCap(img, truth, 0.42, scene.black_level);
  EXPECT_EQ(detect(img), Status::NoTarget);
}

TEST_F(TargetScene, OccludedSecondTargetIsNotDroppedSilently) {
  // The clean target passes the plain fit; the other, a cap hiding 15 % of its rim,
  // only the consensus fit: both count, so the frame is ambiguous.
  const Pose left{0, 20, 0, -150, 0, 800}, right{0, -25, 0, 150, 20, 800};
  cv::Mat img = render(left);
  pasteCard(img, right);
  const Ellipse right_truth = test::diskImage(camera, target, right);
  occludeCap(img, right_truth, 0.15, scene.black_level);
  ASSERT_NEAR(shareAbove(right_truth, chordForShare(right_truth, 0.15)), 0.15, 1e-3);
  EXPECT_EQ(detect(img), Status::AmbiguousTarget);
  ASSERT_EQ(found.size(), 2u);
  options.report_all_targets = true;
  ASSERT_EQ(detect(img), Status::Ok);
  ASSERT_EQ(found.size(), 2u);
  const bool left_first = found[0].ellipse.cx < found[1].ellipse.cx;
  const TargetDetection& l = found[left_first ? 0 : 1];
  const TargetDetection& r = found[left_first ? 1 : 0];
  EXPECT_FALSE(l.robust);
  EXPECT_TRUE(r.robust);
  EXPECT_TRUE(l.spots_found && r.spots_found);
  expectEllipseOfPose(l, left);
  expectEllipseOfPose(r, right, 1.0);
}

TEST_F(TargetScene, ThinBarAcrossTheDiskIsBridged) {
  // A 5 px black bar across the disk, clear of the spots, hides a few per cent of the
  // rim but cuts the outline into two paths, neither tracing 75 % of the ellipse: the
  // consensus ellipse of the larger takes the rim pixels of the other path with it.
  const Pose pose{0, 0, 0, 0, 0, 700};
  const Ellipse truth = test::diskImage(camera, target, pose);
  for (const double offset : {0.5, -0.45}) {  // bar centre below / above the disk centre, in radii
    SCOPED_TRACE(offset);
    cv::Mat img = render(pose);
    const double y = truth.cy + offset * truth.b;
    cv::rectangle(img, cv::Rect(0, int(std::lround(y)) - 2, img.cols, 5), cv::Scalar(scene.black_level), cv::FILLED);
    // The rim hidden: the two crossings of the bar's band.
    const double hidden = shareAbove(truth, y + 3.0) - shareAbove(truth, y - 2.0);
    EXPECT_LT(hidden, 0.07);
    ASSERT_EQ(detect(img), Status::Ok);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_TRUE(found[0].robust);
    EXPECT_TRUE(found[0].spots_found);
    expectEllipseOfPose(found[0], pose, 1.0);
    EXPECT_GE(found[0].traced, 0.9);
  }
}

TEST_F(TargetScene, WhiteOccluderMergedWithTheDisk) {
  const Pose pose{0, 0, 0, 0, 0, 700};
  cv::Mat img = render(pose);
  const Ellipse truth = test::diskImage(camera, target, pose);
  // A white bar over the black card, overlapping the disk's lower rim.
  cv::rectangle(img, cv::Rect(int(truth.cx - 15), int(truth.cy + truth.b - 8), 30, 200),
                cv::Scalar(scene.white_level), cv::FILLED);
  ASSERT_EQ(detect(img), Status::Ok);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].robust);
  expectEllipseOfPose(found[0], pose, 1.0);
}

TEST_F(TargetScene, BorderCutTargetIsFitted) {
  // About a quarter of the disk beyond the left border (thesis fig. 2.27); the spots stay in.
  const Pose pose{0, 0, 0, -240, 0, 700};
  const Ellipse truth = test::diskImage(camera, target, pose);
  ASSERT_LT(truth.cx - truth.a, -10.0);
  ASSERT_GT(truth.cx - 0.5 * truth.a, 0.0);
  ASSERT_EQ(detect(render(pose)), Status::Ok);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_FALSE(found[0].robust);
  expectEllipseOfPose(found[0], pose, 1.0);
  EXPECT_LT(found[0].traced, 0.9);
}

TEST_F(TargetScene, BennettFindsTheTarget) {
  options.method = EllipseMethod::Bennett;
  const Pose pose{20, 30, 0, 0, 0, 800};
  ASSERT_EQ(detect(render(pose)), Status::Ok);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].spots_found);
  EXPECT_GT(found[0].bennett_score, options.bennett_min_score);
  expectEllipseOfPose(found[0], pose);
}

// Tape as bright as the paper across the whole frame, over a bright scene: the disk, the tape
// and the scene are one white region, and the rim is only arcs of the scene's outline, whose
// box spans the frame. The spots stay whole, and the rim is found from them.
TEST_F(TargetScene, RimWithoutAPathOfItsOwnIsFoundFromTheSpots) {
  scene.background_level = 200;
  for (const Pose& pose : {Pose{0, 0, 0, 0, 0, 1000}, Pose{25, -15, 30, 40, -20, 900}}) {
    SCOPED_TRACE(pose.tz_mm);
    cv::Mat img = render(pose);
    const Ellipse truth = test::diskImage(camera, target, pose);
    const int y = static_cast<int>(std::lround(truth.cy + 0.6 * truth.b));
    cv::rectangle(img, cv::Rect(0, y - 4, img.cols, 8), cv::Scalar(scene.white_level), cv::FILLED);
    ASSERT_EQ(detect(img), Status::Ok);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_TRUE(found[0].robust);
    EXPECT_TRUE(found[0].spots_found);
    expectEllipseOfPose(found[0], pose, 1.0);
    EXPECT_GE(found[0].traced, 0.75);
    // Off, no target with its spots is found.
    options.robust_fit = false;
    const Status off = detect(img);
    EXPECT_TRUE(!ok(off) || found.empty() || !found[0].spots_found) << statusName(off);
    options.robust_fit = true;
  }
}

// Two dark dots shaped and spaced like the spots, on paper without a rim round them: no
// target, whichever way the pair is tried.
TEST_F(TargetScene, TwoDotsWithoutARimAreNoTarget) {
  cv::Mat img(camera.height, camera.width, CV_8UC1, cv::Scalar(scene.white_level));
  cv::circle(img, {300, 240}, 5, cv::Scalar(scene.black_level), cv::FILLED, cv::LINE_AA);
  cv::circle(img, {321, 240}, 5, cv::Scalar(scene.black_level), cv::FILLED, cv::LINE_AA);
  const Status st = detect(img);
  EXPECT_TRUE(st == Status::NoTarget || (ok(st) && !found.empty() && !found[0].spots_found)) << statusName(st);
}

// A third dark mark on the disk (the end of a clamp or of tape, broken up by a local
// threshold), where the offset spot could nearly be: the pair that sits best, of one size,
// is the target's spots. A mark of the spots' size where the offset spot could be as well
// leaves the spots undecided: no target with its spots.
TEST_F(TargetScene, AThirdMarkOnTheDiskLeavesThePairThatSitsBest) {
  for (const Pose& pose : {Pose{0, 0, 0, 0, 0, 800}, Pose{30, -20, 40, 30, -20, 700}}) {
    SCOPED_TRACE(pose.tz_mm);
    auto markAt = [&](cv::Mat& img, double y_mm, double radius_mm) {
      const Eigen::Vector3d centre = rotationMatrix(pose) * Eigen::Vector3d(0.0, y_mm, 0.0) + translation(pose);
      const Eigen::Vector2d px = projectIdeal(camera, centre);
      const int r = static_cast<int>(std::lround(radius_mm * camera.fu() / centre.z()));
      cv::circle(img, cv::Point(static_cast<int>(std::lround(px.x())), static_cast<int>(std::lround(px.y()))), r,
                 cv::Scalar(scene.black_level), cv::FILLED, cv::LINE_AA);
    };
    cv::Mat img = render(pose);
    markAt(img, -31.0, 4.0);  // 0.62 of the radius from the centre spot; smaller than a spot
    ASSERT_EQ(detect(img), Status::Ok);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_TRUE(found[0].spots_found);
    const Eigen::Vector2d centre = projectIdeal(camera, translation(pose));
    EXPECT_NEAR(ws.paths[found[0].spot_paths[0]].cx, centre.x(), 1.0);
    EXPECT_NEAR(ws.paths[found[0].spot_paths[0]].cy, centre.y(), 1.0);
    const Eigen::Vector2d offset =
        projectIdeal(camera, rotationMatrix(pose) * Eigen::Vector3d(target.spot_offset_mm, 0.0, 0.0) + translation(pose));
    EXPECT_NEAR(ws.paths[found[0].spot_paths[1]].cx, offset.x(), 1.0);
    EXPECT_NEAR(ws.paths[found[0].spot_paths[1]].cy, offset.y(), 1.0);

    cv::Mat twin = render(pose);
    markAt(twin, -target.spot_offset_mm, target.spot_radius_mm);
    const Status st = detect(twin);
    EXPECT_TRUE(!ok(st) || found.empty() || !found[0].spots_found) << statusName(st);
  }
}

// Seeds on an occluder's two straight edges fit a needle of an ellipse that they trace
// whole. No circle is seen that flat (beyond target_max_tilt_deg): the consensus fit leaves
// such needles out. A path that is a needle (axes 100 and 8 px) gives no ellipse, one as
// flat as a circle at 75 deg does.
TEST(TargetDetection, TheConsensusFitTakesNoNeedle) {
  for (const double minor : {8.0, 26.0}) {
    EllipseWorkspace ws;
    std::vector<EdgePixel> path;
    for (int k = 0; k < 400; ++k) {
      const double t = 2.0 * kPi * k / 400.0;
      const auto x = static_cast<std::int16_t>(std::lround(320.0 + 100.0 * std::cos(t)));
      const auto y = static_cast<std::int16_t>(std::lround(240.0 + minor * std::sin(t)));
      if (path.empty() || path.back().x != x || path.back().y != y)
        path.push_back({x, y, static_cast<std::int16_t>(-std::cos(t) * 4), static_cast<std::int16_t>(-std::sin(t) * 4)});
    }
    EllipseFit fit;
    EllipseTrace trace;
    const Status st = fitEllipseRobust(EllipseOptions{}, path, {640, 480}, ws, fit, trace);
    if (minor < 10.0) {
      EXPECT_FALSE(ok(st)) << fit.ellipse.a << " x " << fit.ellipse.b;
    } else {
      ASSERT_EQ(st, Status::Ok);
      EXPECT_NEAR(fit.ellipse.b, minor, 1.0);
    }
  }
}

// The detection hands the reconstruction its spots' boxes (the spots and their paths' ring),
// also from a reduced or robust pass: each holds its spot's true centre.
TEST_F(TargetScene, TheSpotsBoxesHoldTheSpots) {
  for (const Pose& pose : {Pose{0, 0, 0, 0, 0, 700}, Pose{30, -20, 45, 60, 30, 1100}}) {
    ASSERT_EQ(detect(render(pose)), Status::Ok);
    ASSERT_EQ(found.size(), 1u);
    ASSERT_TRUE(found[0].spots_found);
    const Eigen::Matrix3d R = rotationMatrix(pose);
    const std::array<Eigen::Vector2d, 2> truth{projectIdeal(camera, translation(pose)),
                                               projectIdeal(camera, R * Eigen::Vector3d(target.spot_offset_mm, 0, 0) +
                                                                        translation(pose))};
    const double spotPx = camera.fu() * target.spot_radius_mm / pose.tz_mm;
    for (int k = 0; k < 2; ++k) {
      const cv::Rect& box = found[0].spot_boxes[static_cast<std::size_t>(k)];
      EXPECT_TRUE(box.contains(cv::Point(static_cast<int>(truth[k].x()), static_cast<int>(truth[k].y())))) << k;
      EXPECT_LT(box.width, 2.0 * spotPx + 6.0) << k;
    }
  }
}

TEST(TargetDetection, EmptyAndTinyInputs) {
  EllipseWorkspace ws;
  std::vector<TargetDetection> out;
  Paths paths;
  EXPECT_EQ(detectTarget(EllipseOptions{}, TargetGeometry{}, paths, {640, 480}, ws, out), Status::NoTarget);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(detectEllipses(EllipseOptions{}, paths, {640, 480}, ws, out), Status::NoTarget);
  for (std::int16_t i = 0; i < 5; ++i) paths.pixels.push_back({i, i, 1, 1});
  paths.starts.push_back(5);
  EXPECT_EQ(detectTarget(EllipseOptions{}, TargetGeometry{}, paths, {640, 480}, ws, out), Status::NoTarget);
  EllipseFit fit;
  EllipseTrace trace;
  EXPECT_EQ(fitEllipseRobust(EllipseOptions{}, paths.path(0).first(5), {640, 480}, ws, fit, trace),
            Status::TooFewPoints);
}

}  // namespace
}  // namespace imagepro
