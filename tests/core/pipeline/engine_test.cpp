#include "core/pipeline/engine.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>

#include "core/settings/enum_names.h"
#include "core/source/sources.h"
#include "core/source/virtual_motion.h"
#include "core/source/virtual_renderer.h"
#include "core/tracking/tracker.h"

namespace imagepro {
namespace {

Settings binaryScene(const Pose& pose) {
  Settings s;
  s.virtual_scene.mode = RenderMode::Binary;
  s.virtual_scene.initial_pose = pose;
  return s;
}

Frame render(const Settings& s, const Pose& pose, std::int64_t index = 0) {
  Frame f;
  f.index = index;
  f.timestamp_s = index / s.virtual_scene.frame_rate_hz;
  f.truth = pose;
  renderTarget(s.camera(), s.target, s.virtual_scene, pose, f.image, static_cast<std::uint64_t>(index));
  return f;
}

TEST(Engine, ReconstructsVirtualPoses) {
  const Pose poses[] = {{0, 0, 0, 0, 0, 800}, {30, -20, 75, 40, -30, 700}, {-45, 10, -170, -60, 20, 1000}};
  for (const Pose& truth : poses) {
    const Settings s = binaryScene(truth);
    Engine engine(s);
    FrameResult r;
    engine.process(render(s, truth), r);
    ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
    ASSERT_TRUE(r.pose.has_value());
    EXPECT_EQ(r.reached, ApplicationLevel::Reconstruction);
    EXPECT_LT(rotationAngleBetweenDeg(rotationMatrix(truth), rotationMatrix(*r.pose)), 1.0);
    EXPECT_LT((translation(truth) - translation(*r.pose)).norm(), 0.005 * truth.tz_mm);
    EXPECT_GT(r.edge_pixels, 0u);
    EXPECT_GE(r.paths, 3u);  // rim and two spots
    ASSERT_EQ(r.targets.size(), 1u);
    EXPECT_FALSE(r.detected_region.empty());
  }
}

TEST(Engine, TheSourceInUsePicksItsCamera) {
  const Pose truth{0, 0, 30, 40, -20, 800};
  Settings s = binaryScene(truth);
  // The File source's camera: twice the image plane distance of the virtual one's. A target
  // facing the camera then looks the same twice as far away (Tz doubled), its centre at
  // the same Tx, Ty (the image of X at 2 Tz through 2 d0 is that of X at Tz through d0).
  s.camera(SourceKind::File).image_plane_distance_mm = 2.0 * s.camera(SourceKind::Virtual).image_plane_distance_mm;
  auto source = makeVirtualSource(s);
  Frame frame;
  ASSERT_EQ(source->next(frame), Status::Ok);
  ASSERT_EQ(s.source, SourceKind::Virtual);
  Engine engine(s);
  FrameResult r;
  engine.process(frame, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  EXPECT_LT((translation(truth) - translation(*r.pose)).norm(), 0.005 * truth.tz_mm);

  s.source = SourceKind::File;
  engine.setSettings(s);
  engine.resetTracking();
  engine.process(frame, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  EXPECT_NEAR(r.pose->tz_mm, 2.0 * truth.tz_mm, 0.01 * truth.tz_mm);
  EXPECT_NEAR(r.pose->tx_mm, truth.tx_mm, 0.01 * truth.tz_mm);
  EXPECT_NEAR(r.pose->ty_mm, truth.ty_mm, 0.01 * truth.tz_mm);
  EXPECT_LT(rotationAngleBetweenDeg(rotationMatrix(truth), rotationMatrix(*r.pose)), 1.0);

  // And back: the virtual camera again.
  s.source = SourceKind::Virtual;
  engine.setSettings(s);
  engine.resetTracking();
  engine.process(frame, r);
  ASSERT_EQ(r.status, Status::Ok) << statusName(r.status);
  EXPECT_NEAR(r.pose->tz_mm, truth.tz_mm, 0.005 * truth.tz_mm);
}

TEST(Engine, ApplicationLevelStopsAfterTheChosenStage) {
  const Pose truth{10, 10, 0, 0, 0, 800};
  Settings s = binaryScene(truth);
  s.pipeline.level = ApplicationLevel::Edges;
  Engine engine(s);
  FrameResult r;
  engine.process(render(s, truth), r);
  EXPECT_EQ(r.status, Status::Ok);
  EXPECT_EQ(r.reached, ApplicationLevel::Edges);
  EXPECT_GT(r.edge_pixels, 0u);
  EXPECT_EQ(r.paths, 0u);
  EXPECT_FALSE(r.pose.has_value());
  EXPECT_EQ(r.times[Stage::Connectivity], 0.0);

  s.pipeline.level = ApplicationLevel::Ellipse;
  engine.setSettings(s);
  engine.process(render(s, truth), r);
  EXPECT_EQ(r.reached, ApplicationLevel::Ellipse);
  EXPECT_EQ(r.targets.size(), 1u);
  EXPECT_FALSE(r.pose.has_value());
}

TEST(Engine, OptionChangesTakeEffectOnTheNextFrame) {
  const Pose truth{0, 20, 0, 0, 0, 800};
  Settings s = binaryScene(truth);
  s.pipeline.threshold.method = ThresholdMethod::Manual;
  s.pipeline.threshold.manual_value = 100;
  Engine engine(s);
  FrameResult r;
  const Frame f = render(s, truth);
  engine.process(f, r);
  EXPECT_EQ(r.threshold, 100);
  s.pipeline.threshold.manual_value = 150;
  s.pipeline.edge_method = EdgeMethod::SobelThinning;
  s.pipeline.connectivity = ConnectivityMethod::CN0;
  engine.setSettings(s);
  engine.process(f, r);
  EXPECT_EQ(r.threshold, 150);
  EXPECT_EQ(r.status, Status::Ok) << statusName(r.status);
}

TEST(Engine, BadFramesGiveNamedErrorsAndTheLoopGoesOn) {
  Engine engine;
  FrameResult r;
  Frame empty;
  engine.process(empty, r);
  EXPECT_EQ(r.status, Status::EmptyFrame);

  Frame white;
  white.image = cv::Mat(480, 640, CV_8UC1, cv::Scalar(255));
  engine.process(white, r);
  EXPECT_NE(r.status, Status::Ok);
  EXPECT_FALSE(r.pose.has_value());

  Frame black;
  black.image = cv::Mat(480, 640, CV_8UC1, cv::Scalar(0));
  engine.process(black, r);
  EXPECT_NE(r.status, Status::Ok);

  Frame clutter;
  clutter.image = cv::Mat(480, 640, CV_8UC1, cv::Scalar(20));
  cv::rectangle(clutter.image, cv::Rect(100, 100, 200, 80), cv::Scalar(230), cv::FILLED);
  cv::circle(clutter.image, {450, 300}, 60, cv::Scalar(230), cv::FILLED);  // a disk without spots
  engine.process(clutter, r);
  // Either nothing qualifies, or the best plain ellipse is tried and has no spots.
  EXPECT_TRUE(r.status == Status::NoTarget || r.status == Status::SpotsNotFound) << r.status;
  EXPECT_FALSE(r.pose.has_value());

  // And a good frame right after is processed as usual.
  const Pose truth{0, 0, 0, 0, 0, 800};
  const Settings s = binaryScene(truth);
  engine.setSettings(s);
  engine.process(render(s, truth), r);
  EXPECT_EQ(r.status, Status::Ok);
}

TEST(Engine, TwoTargetsAreAmbiguousNeverAnArbitraryPick) {
  Settings s = binaryScene({});
  const Pose left{0, 0, 0, -120, 0, 900}, right{0, 0, 0, 120, 0, 900};
  const Frame a = render(s, left), b = render(s, right);
  Frame both = a;
  cv::max(a.image, b.image, both.image);
  Engine engine(s);
  FrameResult r;
  engine.process(both, r);
  EXPECT_EQ(r.status, Status::AmbiguousTarget);
  EXPECT_FALSE(r.pose.has_value());
  EXPECT_EQ(r.targets.size(), 2u);
}

TEST(Engine, FileSequenceErrorsAreRowsAndTheLoopGoesOn) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "engine_files";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const Pose truth{0, 15, 30, 0, 0, 800};
  const Settings s = binaryScene(truth);
  ASSERT_TRUE(cv::imwrite((dir / "a.png").string(), render(s, truth).image));
  std::FILE* corrupt = std::fopen((dir / "b.png").string().c_str(), "wb");
  std::fputs("not a png", corrupt);
  std::fclose(corrupt);
  auto source = makeFileSource({(dir / "a.png").string(), (dir / "missing.png").string(), (dir / "b.png").string(),
                                (dir / "a.png").string()});
  Engine engine(s);
  FrameResult r;
  std::vector<Status> statuses;
  while (engine.step(*source, r) != Status::EndOfStream) statuses.push_back(r.status);
  ASSERT_EQ(statuses.size(), 4u);
  EXPECT_EQ(statuses[0], Status::Ok);
  EXPECT_EQ(statuses[1], Status::FileNotFound);
  EXPECT_EQ(statuses[2], Status::FileUnreadable);
  EXPECT_EQ(statuses[3], Status::Ok);
}

// Still images are not a motion: a file never limits the search in the next one.
TEST(Engine, ImageFilesAreSearchedWhole) {
  Settings s = binaryScene({});
  Engine engine(s);
  FrameResult r;
  const Pose poses[] = {{0, 0, 0, -150, -80, 800}, {0, 0, 0, -140, -70, 800}, {0, 30, 0, 160, 90, 800}};
  for (int i = 0; i < 3; ++i) {
    Frame f = render(s, poses[i], i);
    f.name = "still" + std::to_string(i) + ".png";
    engine.process(f, r);
    EXPECT_EQ(r.status, Status::Ok) << i;
    EXPECT_EQ(r.search_region, cv::Rect(0, 0, 640, 480)) << i;
  }
}

// Thesis 3.4's goal: the target wholly inside the estimated region in every frame.
TEST(Engine, TrackedRegionAlwaysHoldsTheTarget) {
  for (const MotionKind motion : {MotionKind::Sinusoid, MotionKind::SawTooth, MotionKind::Pendulum}) {
    Settings s;
    s.virtual_scene.mode = RenderMode::Binary;
    s.virtual_scene.motion.kind = motion;
    s.virtual_scene.motion.axis = PoseAxis::Tx;
    s.virtual_scene.motion.amplitude = 150;
    s.virtual_scene.motion.period_s = 3;
    s.pipeline.tracking.mode = TrackingMode::Corners2D;
    VirtualSource source(s);
    Engine engine(s);
    FrameResult r;
    int tracked = 0, inside = 0;
    double area = 0;
    for (int i = 0; i < 150; ++i) {
      ASSERT_EQ(engine.step(source, r), Status::Ok);
      ASSERT_EQ(r.status, Status::Ok) << "frame " << i << ": " << statusName(r.status);
      if (r.search_region.area() < r.image_size.area()) {
        ++tracked;
        const cv::Rect2d box = projectedTargetBox(s.camera(), s.target, *r.truth);
        const cv::Rect2d region(r.search_region);
        if ((box & region).area() >= box.area() - 1e-6)
          ++inside;
        else
          ADD_FAILURE() << "frame " << i << ": target box " << box << " not inside " << region;
        area += static_cast<double>(r.search_region.area()) / r.image_size.area();
      }
    }
    EXPECT_GE(tracked, 140) << enumName(motion);
    EXPECT_EQ(inside, tracked) << "motion " << static_cast<int>(motion);
    EXPECT_LE(area / tracked, 0.10);
  }
}

// After one detection the next frame is searched about it (the target's motion is not
// known yet): a target that stayed is found there, one that jumped away by the whole frame
// in the same frame, so the guess never costs a pose.
TEST(Engine, OneDetectionGivesARegionAndItsMissTheWholeFrame) {
  Settings s;
  s.virtual_scene.mode = RenderMode::Grey;
  s.pipeline.tracking.mode = TrackingMode::Corners2D;
  const Pose here{10, 20, 0, -150, -80, 900}, there{10, 20, 0, 170, 90, 900};
  for (const bool jumps : {false, true}) {
    Engine engine(s);
    FrameResult first, second;
    engine.process(render(s, here, 0), first);
    ASSERT_EQ(first.status, Status::Ok) << statusName(first.status);
    EXPECT_EQ(first.search_region, cv::Rect(0, 0, 640, 480));
    engine.process(render(s, jumps ? there : here, 1), second);
    ASSERT_EQ(second.status, Status::Ok) << "jumps " << jumps << ": " << statusName(second.status);
    EXPECT_LT(rotationAngleBetweenDeg(rotationMatrix(jumps ? there : here), rotationMatrix(*second.pose)), 1.0);
    if (jumps) {
      EXPECT_EQ(second.search_region, cv::Rect(0, 0, 640, 480)) << "the region missed: the whole frame";
    } else {
      EXPECT_LT(second.search_region.area(), 640 * 480 / 4) << "searched about the first detection";
      EXPECT_TRUE(second.search_region.contains(second.detected_region.tl()));
    }
  }
}

// A tracked region is read where it lies in the frame: its histogram and binary image
// are those of the frame's pixels there, and the frame is never written.
TEST(Engine, TrackedRegionIsReadInPlaceAndTheFrameStaysIntact) {
  Settings s;
  s.virtual_scene.mode = RenderMode::Grey;
  s.virtual_scene.noise_sigma = 3.0;
  s.virtual_scene.motion.kind = MotionKind::Sinusoid;
  s.virtual_scene.motion.axis = PoseAxis::Tx;
  s.virtual_scene.motion.amplitude = 100;
  s.virtual_scene.motion.period_s = 2;
  s.pipeline.tracking.mode = TrackingMode::Corners2D;
  // The whole frames before tracking starts are compared too: at full size (a coarse
  // search's binary image is the reduced one, enlarged: stage_chain_test.cpp).
  s.pipeline.binarization.coarse_search = false;
  VirtualSource source(s);
  Engine engine(s);
  FrameResult r;
  Frame frame;
  int tracked = 0;
  for (int i = 0; i < 40; ++i) {
    ASSERT_EQ(source.next(frame), Status::Ok);
    const cv::Mat before = frame.image.clone();
    engine.process(frame, r);
    ASSERT_EQ(r.status, Status::Ok) << "frame " << i << ": " << statusName(r.status);
    EXPECT_EQ(cv::countNonZero(frame.image != before), 0) << "frame " << i;
    const cv::Mat region = before(r.search_region);
    // A tracked region's histogram counts every k-th row, at least 8192 pixels, each count
    // times k (stage_chain.h); the whole frame's every row.
    const bool whole = r.search_region.area() == r.image_size.area();
    const int k = whole ? 1 : std::max(1, r.search_region.area() / 8192);
    Histogram expected{};
    for (int y = 0; y < region.rows; y += k)
      for (int x = 0; x < region.cols; ++x) expected[region.at<std::uint8_t>(y, x)] += static_cast<std::uint32_t>(k);
    EXPECT_EQ(r.histogram, expected) << "frame " << i;
    cv::Mat expected_binary;
    cv::threshold(region, expected_binary, r.threshold, 255, cv::THRESH_BINARY);
    const cv::Mat& binary = engine.binaryImage();
    ASSERT_EQ(binary.size(), region.size()) << "frame " << i;
    EXPECT_EQ(cv::countNonZero(binary != expected_binary), 0) << "frame " << i;
    EXPECT_NE(binary.datastart, frame.image.datastart);
    if (r.search_region.area() < r.image_size.area()) ++tracked;
  }
  EXPECT_GE(tracked, 30);
}

}  // namespace
}  // namespace imagepro
