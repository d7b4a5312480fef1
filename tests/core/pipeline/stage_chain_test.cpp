#include "core/pipeline/stage_chain.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <vector>

#include "core/segmentation/histogram.h"
#include "core/segmentation/threshold.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {
namespace {

// A grey virtual frame of the target at `pose`, on the thesis's plain background.
cv::Mat render(const Settings& s, const Pose& pose) {
  VirtualSceneOptions scene = s.virtual_scene;
  scene.backdrop = Backdrop::Plain;
  cv::Mat image;
  renderTarget(s.camera(), s.target, scene, pose, image);
  return image;
}

double rotationErrorDeg(const Pose& a, const Pose& b) {
  return rotationAngleBetweenDeg(rotationMatrix(a), rotationMatrix(b));
}

// The default Virtual scene, a lit room around the card: the exact pose holds at every
// distance and tilt of the Virtual source's range.
TEST(StageChain, TheDefaultRoomSceneGivesTheExactPose) {
  const Settings s;
  ASSERT_EQ(s.virtual_scene.backdrop, Backdrop::Room);
  StageChain chain;
  for (const Pose& truth : {Pose{0, 0, 0, 0, 0, 800}, Pose{20, -15, 30, -120, 10, 900}, Pose{-40, 25, 80, 90, -60, 650},
                            Pose{10, 50, -20, 150, 80, 1200}, Pose{-30, -10, 170, -200, -100, 1000}}) {
    SCOPED_TRACE(truth.tz_mm);
    cv::Mat image;
    renderTarget(s.camera(), s.target, s.virtual_scene, truth, image);
    FrameResult result;
    runStageChain(s, image, {}, TargetsToReconstruct::Best, chain, result);
    ASSERT_EQ(result.status, Status::Ok) << statusName(result.status);
    ASSERT_TRUE(result.pose.has_value());
    EXPECT_LT(rotationErrorDeg(truth, *result.pose), 0.5);
    EXPECT_LT((translation(truth) - translation(*result.pose)).norm(), 0.003 * truth.tz_mm);
  }
}

// The target in the shade on the left, a bright window filling the right half: the global
// threshold separates the window from the room and the target's disk, dimmer than the
// threshold, is lost with the room; the local second pass finds it.
TEST(StageChain, FindsATargetInTheShadeBesideABrightWindow) {
  Settings s;
  s.virtual_scene.noise_sigma = 2.0;
  s.virtual_scene.blur_sigma_px = 0.7;
  const Pose truth{20, -15, 30, -120, 10, 900};
  cv::Mat grey = render(s, truth);
  grey.convertTo(grey, CV_8UC1, 0.3);                             // the room in the shade
  grey(cv::Rect(400, 0, 240, 480)).setTo(250);                    // the window
  cv::GaussianBlur(grey, grey, cv::Size(3, 3), 0.6);

  StageChain chain;
  FrameResult global, local;
  Settings thesis = s;
  thesis.pipeline.binarization.mode = Binarization::Global;
  runStageChain(thesis, grey, {}, TargetsToReconstruct::Best, chain, global);
  EXPECT_FALSE(ok(global.status)) << "the global threshold alone should miss this target";

  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, local);
  ASSERT_EQ(local.status, Status::Ok) << statusName(local.status);
  ASSERT_TRUE(local.pose.has_value());
  EXPECT_LT(rotationErrorDeg(truth, *local.pose), 1.0);
  EXPECT_LT((translation(truth) - translation(*local.pose)).norm(), 0.005 * truth.tz_mm);
  EXPECT_EQ(local.threshold, global.threshold);  // the frame's threshold is still reported
  // The local pass's buffers are the ones kept: its edges lie on the found target.
  EXPECT_TRUE(cv::Rect(0, 0, 640, 480).contains(local.detected_region.tl()));
  EXPECT_GT(local.times[Stage::Threshold], 0.0);
}

// On a clean frame the thesis's threshold finds the target and no second pass runs: the
// default gives exactly the global mode's result.
TEST(StageChain, CleanFramesKeepTheThesisResult) {
  Settings s;
  const Pose truth{10, 25, -60, 40, -30, 700};
  const cv::Mat grey = render(s, truth);
  Settings thesis = s;
  thesis.pipeline.binarization.mode = Binarization::Global;
  StageChain chain;
  FrameResult a, b;
  runStageChain(thesis, grey, {}, TargetsToReconstruct::Best, chain, a);
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, b);
  ASSERT_EQ(a.status, Status::Ok);
  ASSERT_EQ(b.status, Status::Ok);
  EXPECT_EQ(a.edge_pixels, b.edge_pixels);
  EXPECT_EQ(a.pose->rx_deg, b.pose->rx_deg);
  EXPECT_EQ(a.pose->tz_mm, b.pose->tz_mm);
}

// A frame without a target misses in both passes: the first pass's report stands.
TEST(StageChain, ADoubleMissReportsTheFirstPass) {
  Settings s;
  cv::Mat grey(480, 640, CV_8UC1, cv::Scalar(90));
  cv::rectangle(grey, cv::Rect(100, 100, 200, 120), cv::Scalar(200), cv::FILLED);
  StageChain chain;
  FrameResult global, both;
  Settings thesis = s;
  thesis.pipeline.binarization.mode = Binarization::Global;
  runStageChain(thesis, grey, {}, TargetsToReconstruct::Best, chain, global);
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, both);
  EXPECT_FALSE(ok(global.status));
  EXPECT_EQ(both.status, global.status);
  EXPECT_EQ(both.edge_pixels, global.edge_pixels);
  EXPECT_EQ(chain.edges.size(), global.edge_pixels);  // the buffers are the first pass's again
  EXPECT_FALSE(both.pose.has_value());
}

// The chain stops after the application level; the local pass never runs for a stage
// that cannot miss the target.
TEST(StageChain, StopsAtTheApplicationLevel) {
  Settings s;
  s.pipeline.level = ApplicationLevel::Connectivity;
  const cv::Mat grey = render(s, Pose{0, 0, 0, 0, 0, 800});
  StageChain chain;
  FrameResult r;
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  EXPECT_EQ(r.status, Status::Ok);
  EXPECT_EQ(r.reached, ApplicationLevel::Connectivity);
  EXPECT_GE(chain.paths.pathCount(), 3u);
  EXPECT_TRUE(r.targets.empty());
  EXPECT_EQ(r.times[Stage::Ellipse], 0.0);
}

// Every target of the frame reconstructed, each with its own status and pose.
TEST(StageChain, EveryTargetGetsItsOwnPose) {
  Settings s;
  const Pose left{0, 20, 0, -150, 0, 900}, right{0, -20, 0, 150, 0, 900};
  cv::Mat a = render(s, left), b = render(s, right);
  cv::Mat grey = a.clone();
  b(cv::Rect(320, 0, 320, 480)).copyTo(grey(cv::Rect(320, 0, 320, 480)));
  StageChain chain;
  FrameResult r;
  runStageChain(s, grey, {}, TargetsToReconstruct::Every, chain, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  ASSERT_EQ(r.targets.size(), 2u);
  for (const TargetSummary& t : r.targets) {
    ASSERT_EQ(t.status, Status::Ok);
    ASSERT_TRUE(t.pose.has_value());
    const Pose& truth = t.pose->tx_mm < 0 ? left : right;
    EXPECT_LT(rotationErrorDeg(truth, *t.pose), 1.0);
  }
  // The best-target run of the same frame calls it ambiguous.
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  EXPECT_EQ(r.status, Status::AmbiguousTarget);
}

// The target beside a look-alike: a white disk on a dark card with two dark marks half its
// radius apart, like the spots, but 6 px (0.14 R) below its centre, within what the ellipse
// stage allows. The ellipse stage takes both for targets; no pose of the target puts its
// spots where the look-alike has them and its rim where the look-alike's is, so the frame
// is the target's, with its pose. Two targets that both reconstruct stay AmbiguousTarget
// (EveryTargetGetsItsOwnPose).
TEST(StageChain, ALookAlikeWithoutAPoseDoesNotMakeTheFrameAmbiguous) {
  Settings s;
  const Pose truth{0, 20, 0, -150, 0, 900};
  cv::Mat grey = render(s, truth);
  const cv::Point centre(470, 240);
  const int radius = 44;  // the target's image radius at 900 mm
  cv::rectangle(grey, cv::Rect(centre.x - 60, centre.y - 60, 120, 120), cv::Scalar(s.virtual_scene.black_level),
                cv::FILLED);
  cv::circle(grey, centre, radius, cv::Scalar(s.virtual_scene.white_level), cv::FILLED, cv::LINE_AA);
  cv::circle(grey, centre + cv::Point(0, 6), 5, cv::Scalar(s.virtual_scene.black_level), cv::FILLED, cv::LINE_AA);
  cv::circle(grey, centre + cv::Point(22, 6), 5, cv::Scalar(s.virtual_scene.black_level), cv::FILLED, cv::LINE_AA);
  StageChain chain;
  FrameResult r;
  runStageChain(s, grey, {}, TargetsToReconstruct::Every, chain, r);
  ASSERT_EQ(r.targets.size(), 2u) << "the ellipse stage takes the look-alike for a target";
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  ASSERT_TRUE(r.pose.has_value());
  EXPECT_LT(rotationErrorDeg(truth, *r.pose), 1.0);
  EXPECT_LT(std::abs(r.pose->tx_mm - truth.tx_mm), 2.0);
  EXPECT_LT(r.detected_region.x, 320) << "the detected region is the target's";
}

// A far, steeply seen target on a black background, its card (black level 40) brighter
// than the background: in the global and the wide local windows' binary images card and
// disk are one white blob, and only the last local pass, with a narrow window, separates
// the disk. With the window set in the settings (no narrow pass) it is not found.
TEST(StageChain, AFarTargetOnABlackBackgroundIsFoundThroughTheNarrowWindow) {
  Settings s;
  s.virtual_scene.background_level = 0;
  s.virtual_scene.black_level = 40;
  s.virtual_scene.blur_sigma_px = 1.0;
  s.virtual_scene.noise_sigma = 2.0;
  StageChain chain;
  FrameResult r;
  for (const Pose& truth : {Pose{55, 0, 30, 100, 50, 2200}, Pose{58, 0, 30, 100, 50, 2400}}) {
    const cv::Mat grey = render(s, truth);
    s.pipeline.binarization.window_px = 0;
    runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
    ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
    ASSERT_TRUE(r.pose.has_value());
    EXPECT_LT(rotationErrorDeg(truth, *r.pose), 1.0);
    s.pipeline.binarization.window_px = 41;
    runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
    EXPECT_EQ(r.status, Status::NoTarget) << statusName(r.status);
  }
}

// A set of two targets (settings "targets", target_set.h) whose offset spots sit at 0.4 and
// 0.6 of the radius: each frame's target is told by its print at every distance and tilt
// of the grid, with its own pose; the settings' one target (0.5) belongs to neither and is
// UnknownTarget; without a set the same frame is the lone target, id 0.
TEST(StageChain, ATargetOfASetIsToldByWhereItsOffsetSpotSits) {
  Settings s;
  s.virtual_scene.blur_sigma_px = 0.8;
  s.virtual_scene.noise_sigma = 2.0;
  TargetSpec near, far;
  near.id = 1;
  near.name = "link 1";
  near.geometry.spot_offset_mm = 20.0;
  far.id = 2;
  far.name = "link 2";
  far.geometry.spot_offset_mm = 30.0;
  s.targets = {near, far};
  StageChain chain;
  FrameResult r;
  int told = 0;
  for (const double z : {500.0, 900.0, 1400.0, 2000.0})
    for (const double tilt : {0.0, 30.0, 55.0})
      for (const TargetSpec& printed : s.targets) {
        const Pose truth{tilt, 0.4 * tilt, 35.0 + z / 50.0, 60.0, -40.0, z};
        SCOPED_TRACE(testing::Message() << "id " << printed.id << " at " << z << " mm, " << tilt << " deg");
        Settings scene = s;
        scene.target = printed.geometry;  // what the renderer draws
        const cv::Mat grey = render(scene, truth);
        runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
        ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
        EXPECT_EQ(r.target_id, printed.id);
        ASSERT_TRUE(r.pose.has_value());
        // Seen face-on the rim's two circles are close and the pose may be the one halfway
        // between them, within ambiguity_tolerance_deg, as for a lone target.
        EXPECT_LT(rotationErrorDeg(truth, *r.pose), tilt == 0.0 ? 3.0 : 1.0);
        EXPECT_LT(std::abs(r.pose->tz_mm - z), 0.01 * z);
        told += r.target_id == printed.id;
      }
  EXPECT_EQ(told, 24);

  const Pose truth{20, 10, 30, 50, 20, 900};
  const cv::Mat lone = render(Settings{}, truth);  // offset spot at 0.5 of the radius
  runStageChain(s, lone, {}, TargetsToReconstruct::Best, chain, r);
  EXPECT_EQ(r.status, Status::UnknownTarget) << statusName(r.status);
  EXPECT_EQ(r.target_id, -1);
  EXPECT_FALSE(r.pose.has_value());
  runStageChain(Settings{}, lone, {}, TargetsToReconstruct::Best, chain, r);
  EXPECT_EQ(r.status, Status::Ok) << statusName(r.status);
  EXPECT_EQ(r.target_id, kLoneTargetId);
}

// A far target blurred until its spots no longer show as dark paths in the binary image,
// and a sharp white ring with a dark centre beside it: the ellipse stage finds no target
// and ranks the ring, which holds a dark path, above the target's plain disk. The ring
// gives no pose (one spot); the runner-up, the target, does, through the reconstruction's
// own spot search. The ring alone stays without a pose.
TEST(StageChain, ATargetWhoseSpotsTheBinaryImageLosesIsFoundBehindARing) {
  Settings s;
  s.virtual_scene.blur_sigma_px = 2.0;
  const Pose truth{20, 30, 10, -300, 0, 2200};
  cv::Mat grey = render(s, truth);
  auto drawRing = [&s](cv::Mat& image) {
    const cv::Point centre(470, 330);
    cv::ellipse(image, centre, cv::Size(30, 22), 20, 0, 360, cv::Scalar(230), cv::FILLED, cv::LINE_AA);
    cv::circle(image, centre, 6, cv::Scalar(s.virtual_scene.black_level), cv::FILLED, cv::LINE_AA);
  };
  drawRing(grey);
  StageChain chain;
  FrameResult r;
  s.pipeline.level = ApplicationLevel::Ellipse;
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok);
  ASSERT_FALSE(chain.detections.front().spots_found) << "the spots must be lost to the binary image";
  EXPECT_GT(chain.detections.front().ellipse.cx, 400) << "the ring is ranked first";
  s.pipeline.level = ApplicationLevel::Reconstruction;
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  ASSERT_TRUE(r.pose.has_value());
  EXPECT_LT(rotationErrorDeg(truth, *r.pose), 1.0);
  EXPECT_LT(std::abs(r.pose->tz_mm - truth.tz_mm), 0.02 * truth.tz_mm);  // 1.4 %: 2 px of blur on a small rim
  EXPECT_LT(r.detected_region.x, 320) << "the detected region is the target's";

  cv::Mat ringOnly(grey.size(), CV_8UC1, cv::Scalar(s.virtual_scene.background_level));
  drawRing(ringOnly);
  runStageChain(s, ringOnly, {}, TargetsToReconstruct::Best, chain, r);
  EXPECT_FALSE(r.pose.has_value());
  EXPECT_FALSE(ok(r.status)) << statusName(r.status);
}

// Spots 2 px across at 2.5 m (a 3.2 mm spot radius seen by the default camera), blurred,
// noisy and JPEG-compressed, are found: the frame gets a pose (or, far and tilted, the
// named doubt between its two poses), never SpotsNotFound.
TEST(StageChain, FindsSpotsTwoPixelsAcrossAtTwoAndAHalfMetres) {
  Settings s;
  s.target.spot_radius_mm = 3.2;
  s.virtual_scene.blur_sigma_px = 0.8;
  s.virtual_scene.noise_sigma = 2.0;
  const double spot_px = 2.0 * s.target.spot_radius_mm * s.camera().fu() / 2500.0;
  ASSERT_LT(spot_px, 2.1);
  const Pose poses[] = {{20, -10, 30, 50, -40, 2500}, {-15, 25, -120, -200, 100, 2500}, {5, 5, 170, 150, 120, 2500},
                        {30, 0, 60, 0, 0, 2500},      {0, -30, -60, -100, -150, 2500}};
  StageChain chain;
  FrameResult r;
  int posed = 0;
  for (const Pose& truth : poses) {
    cv::Mat grey = render(s, truth);
    std::vector<std::uint8_t> jpeg;
    ASSERT_TRUE(cv::imencode(".jpg", grey, jpeg, {cv::IMWRITE_JPEG_QUALITY, 75}));
    grey = cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE);
    runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
    EXPECT_TRUE(r.status == Status::Ok || r.status == Status::AmbiguousPose) << statusName(r.status);
    if (!r.pose) continue;
    ++posed;
    EXPECT_LT(rotationErrorDeg(truth, *r.pose), 5.0);
    EXPECT_LT((translation(truth) - translation(*r.pose)).norm(), 0.005 * truth.tz_mm);
  }
  // Measured: 3 poses within 3.3 deg, 2 AmbiguousPose (at 2.5 m the spots of a target
  // tilted 20-30 deg may not tell its two poses apart). Without the model-guided search
  // all five were SpotsNotFound.
  EXPECT_GE(posed, 3);
}

}  // namespace
}  // namespace imagepro

namespace imagepro {
namespace {

// A tracked region's histogram is taken on every k-th row (at least 8192 pixels) and each
// count scaled back by k: its threshold is the whole region's to a grey level, its total
// the region's area to a sampled row's width, and the region's pose the same.
TEST(StageChain, ATrackedRegionsSampledHistogramKeepsItsThreshold) {
  Settings s;
  s.virtual_scene.noise_sigma = 3.0;
  s.virtual_scene.blur_sigma_px = 0.8;
  for (const Pose& truth : {Pose{10, 25, -60, 40, -30, 500}, Pose{-30, 5, 100, -150, 80, 900}}) {
    const cv::Mat grey = render(s, truth);
    StageChain chain;
    FrameResult whole, tracked;
    runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, whole);
    ASSERT_EQ(whole.status, Status::Ok);
    cv::Rect region = whole.detected_region;
    region -= cv::Point(40, 40);
    region += cv::Size(80, 80);
    region &= cv::Rect(0, 0, grey.cols, grey.rows);
    ASSERT_GT(region.area(), 2 * 8192) << "sampled";
    runStageChain(s, grey, region, TargetsToReconstruct::Best, chain, tracked);
    ASSERT_EQ(tracked.status, Status::Ok) << statusName(tracked.status);
    Histogram full;
    computeHistogram(grey(region), full);
    int fullThreshold = -1;
    ASSERT_EQ(computeThreshold(s.pipeline.threshold, full, fullThreshold), Status::Ok);
    EXPECT_NEAR(tracked.threshold, fullThreshold, 1);
    std::int64_t total = 0;
    for (const std::uint32_t c : tracked.histogram) total += c;
    const int rowStep = region.area() / 8192;
    EXPECT_NEAR(static_cast<double>(total), region.area(), rowStep * region.width);
    EXPECT_LT(rotationErrorDeg(*whole.pose, *tracked.pose), 0.05);
  }
}

// The coarse search (stage_chain.h): a clean frame is found on the reduced image, and the
// pose, reconstructed from the frame itself, is the full-size search's to within the
// noise of where the crop and the rim's crossings start.
TEST(StageChainCoarse, TheReducedSearchGivesTheFullSizePose) {
  Settings s;
  s.virtual_scene.noise_sigma = 2.0;
  s.virtual_scene.blur_sigma_px = 0.7;
  Settings full = s;
  full.pipeline.binarization.coarse_search = false;
  for (const Pose& truth : {Pose{10, 25, -60, 40, -30, 700}, Pose{-30, 5, 100, -150, 80, 1400}, Pose{0, 40, 20, 120, 0, 2000}}) {
    const cv::Mat grey = render(s, truth);
    StageChain chain;
    FrameResult coarse, whole;
    runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, coarse);
    const int factor = chain.reported_factor;
    runStageChain(full, grey, {}, TargetsToReconstruct::Best, chain, whole);
    ASSERT_EQ(coarse.status, Status::Ok) << statusName(coarse.status);
    ASSERT_EQ(whole.status, Status::Ok) << statusName(whole.status);
    EXPECT_EQ(factor, 2) << "found on the image reduced twice";
    EXPECT_EQ(chain.reported_factor, 1);
    // Measured: 0.006-0.07 deg and 0.02-0.16 mm apart, each 0.07-0.47 deg from the truth.
    EXPECT_LT(rotationErrorDeg(*coarse.pose, *whole.pose), 0.2);
    EXPECT_LT((translation(*coarse.pose) - translation(*whole.pose)).norm(), 5e-4 * truth.tz_mm);
    EXPECT_LT(rotationErrorDeg(truth, *coarse.pose), 1.0);
  }
}

// What a reduced pass reports is given at the frame's size: its edges and paths at their
// blocks' centres, its binary image enlarged on demand.
TEST(StageChainCoarse, AReducedPassIsShownAtTheFramesSize) {
  Settings s;
  const cv::Mat grey = render(s, Pose{15, -20, 45, 30, 20, 900});
  StageChain chain;
  FrameResult r;
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  ASSERT_EQ(chain.reported_factor, 2);
  ASSERT_EQ(chain.binary.size(), cv::Size(320, 240));
  const cv::Mat& shown = regionBinary(chain);
  ASSERT_EQ(shown.size(), grey.size());
  for (int y = 0; y < shown.rows; ++y)
    for (int x = 0; x < shown.cols; ++x)
      ASSERT_EQ(shown.at<std::uint8_t>(y, x), chain.binary.at<std::uint8_t>(y / 2, x / 2)) << x << "," << y;
  ASSERT_FALSE(chain.edges.empty());
  EXPECT_EQ(chain.paths.pixels.size(), chain.edges.size());
  for (const EdgePixel& p : chain.edges) {
    ASSERT_TRUE(cv::Rect(0, 0, 640, 480).contains(cv::Point(p.x, p.y)));
    ASSERT_EQ(p.x % 2, 0);  // the top-left pixel of the block: (k - 1) / 2 = 0 for k = 2
    ASSERT_EQ(p.y % 2, 0);
  }
  // The detected region (the tracker's next search) is in the frame's coordinates: it
  // holds the rim found at full size.
  EXPECT_TRUE(r.detected_region.contains(cv::Point(static_cast<int>(std::lround(chain.reconstruction.ellipse.cx)),
                                                   static_cast<int>(std::lround(chain.reconstruction.ellipse.cy)))));
  const Ellipse& rim = chain.reconstruction.ellipse;
  EXPECT_GE(r.detected_region.width, 2 * rim.b - 4);
  EXPECT_LE(r.detected_region.width, 2 * rim.a + 4);
}

// Below the pose's stage nothing tells a reduced pass's miss from the target's absence:
// the stages' own views (imagepro-cli detect, edges) search the frame itself. A tracked
// region is searched at its own size.
TEST(StageChainCoarse, AChainStoppingBeforeThePoseSearchesTheFullSize) {
  Settings s;
  s.pipeline.level = ApplicationLevel::Ellipse;
  const cv::Mat grey = render(s, Pose{0, 0, 0, 0, 0, 800});
  StageChain chain;
  FrameResult r;
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok);
  EXPECT_EQ(chain.reported_factor, 1);
  EXPECT_EQ(chain.binary.size(), grey.size());
  // A tracked region, even one as wide as the frame, is searched at its own size.
  s.pipeline.level = ApplicationLevel::Reconstruction;
  runStageChain(s, grey, cv::Rect(0, 60, 640, 360), TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  EXPECT_EQ(chain.reported_factor, 1);
}

// A target whose card shows as a ring one pixel wide: at half size the ring fades into
// the white around it and the disk with it, so the reduced passes miss; the full-size
// passes find it (the rim from the spots, detect.h, is left to the full-size passes).
TEST(StageChainCoarse, AMissAtTheReducedSizeFallsThroughToTheFullSize) {
  Settings s;
  s.virtual_scene.card_size_mm = 102.0;
  s.virtual_scene.background_level = 245;
  const Pose truth{0, 10, 30, 0, 0, 800};
  const cv::Mat grey = render(s, truth);
  StageChain chain;
  FrameResult r;
  runStageChain(s, grey, {}, TargetsToReconstruct::Best, chain, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  EXPECT_EQ(chain.reported_factor, 1) << "found by a full-size pass";
  EXPECT_EQ(chain.binary.size(), grey.size());
  EXPECT_LT(rotationErrorDeg(truth, *r.pose), 1.0);
  EXPECT_LT((translation(truth) - translation(*r.pose)).norm(), 0.005 * truth.tz_mm);
}

}  // namespace
}  // namespace imagepro
