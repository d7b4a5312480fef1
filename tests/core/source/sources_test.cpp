#include "core/source/sources.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <atomic>
#include <cmath>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <thread>

#include "core/source/virtual_renderer.h"
#include "support/expect_pose.h"

namespace imagepro {
namespace {

namespace fs = std::filesystem;

using test::expectPose;
// The truth a source reports is the very pose computed: only rounding apart.
constexpr double kSamePose = 1e-12;

TEST(FileSource, DeliversEveryFileAndGoesOnAfterErrors) {
  const fs::path dir = fs::path(IMAGEPRO_TEST_TMP) / "source" / "file_source";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const cv::Mat a(20, 30, CV_8UC1, cv::Scalar(40));
  const cv::Mat b(10, 15, CV_8UC1, cv::Scalar(200));
  cv::imwrite((dir / "a.png").string(), a);
  cv::imwrite((dir / "b.pgm").string(), b);
  std::ofstream((dir / "bad.png").string()) << "garbage";
  auto source = makeFileSource({(dir / "a.png").string(), (dir / "gone.png").string(), (dir / "bad.png").string(),
                                (dir / "b.pgm").string()});
  EXPECT_EQ(source->frameRateHz(), 0.0);
  Frame f;
  ASSERT_EQ(source->next(f), Status::Ok);
  EXPECT_EQ(f.index, 0);
  EXPECT_EQ(f.name, "a.png");
  EXPECT_EQ(cv::norm(f.image, a, cv::NORM_INF), 0.0);
  EXPECT_FALSE(f.truth.has_value());

  EXPECT_EQ(source->next(f), Status::FileNotFound);
  EXPECT_EQ(f.index, 1);
  EXPECT_EQ(f.name, "gone.png");
  EXPECT_TRUE(f.image.empty());
  EXPECT_NE(source->lastError().find("gone.png"), std::string::npos);

  EXPECT_EQ(source->next(f), Status::FileUnreadable);
  EXPECT_EQ(f.name, "bad.png");
  EXPECT_NE(source->lastError().find("bad.png"), std::string::npos);

  ASSERT_EQ(source->next(f), Status::Ok);
  EXPECT_EQ(f.index, 3);
  EXPECT_EQ(f.name, "b.pgm");
  EXPECT_EQ(cv::norm(f.image, b, cv::NORM_INF), 0.0);

  EXPECT_EQ(source->next(f), Status::EndOfStream);
  EXPECT_EQ(source->next(f), Status::EndOfStream);
  EXPECT_EQ(makeFileSource({})->next(f), Status::EndOfStream);
}

Settings virtualSettings() {
  Settings s;
  s.virtual_scene.mode = RenderMode::Binary;
  s.virtual_scene.frame_rate_hz = 20;
  s.virtual_scene.motion.kind = MotionKind::Sinusoid;
  s.virtual_scene.motion.axis = PoseAxis::Tx;
  s.virtual_scene.motion.amplitude = 80;
  s.virtual_scene.motion.period_s = 2;
  return s;
}

TEST(VirtualSource, FramesCarryIndexTimeAndExactPose) {
  const Settings settings = virtualSettings();
  auto source = makeVirtualSource(settings);
  EXPECT_EQ(source->frameRateHz(), 20.0);
  // The status bar's text names the mode and motion by their display names.
  EXPECT_EQ(source->describe(), "virtual 20 Hz, Binary, Sinusoid");
  Frame f;
  for (int i = 0; i < 12; ++i) {
    ASSERT_EQ(source->next(f), Status::Ok);
    EXPECT_EQ(f.index, i);
    EXPECT_DOUBLE_EQ(f.timestamp_s, i / 20.0);
    ASSERT_TRUE(f.truth.has_value());
    expectPose(*f.truth, virtualPoseAt(settings.virtual_scene, i / 20.0), kSamePose);
    cv::Mat expected;
    renderTarget(settings.camera(), settings.target, settings.virtual_scene, *f.truth, expected, i);
    EXPECT_EQ(cv::norm(f.image, expected, cv::NORM_INF), 0.0);
  }
  // Frame 10 is at t = 0.5 s, a quarter of the 2 s period: the sinusoid's crest.
  EXPECT_NEAR(source->poseAt(10).tx_mm, settings.virtual_scene.initial_pose.tx_mm + 80.0, 1e-9);
}

TEST(VirtualSource, KeysSettingsAndRestartApplyFromTheNextFrame) {
  Settings settings = virtualSettings();
  settings.virtual_scene.motion.kind = MotionKind::Static;
  auto source = makeVirtualSource(settings);
  Frame f;
  ASSERT_EQ(source->next(f), Status::Ok);
  expectPose(*f.truth, settings.virtual_scene.initial_pose, kSamePose);
  source->pressKey(VirtualKey::TxPlus);
  source->pressKey(VirtualKey::TxPlus);
  source->pressKey(VirtualKey::RzMinus);
  ASSERT_EQ(source->next(f), Status::Ok);
  Pose want = settings.virtual_scene.initial_pose;
  want.tx_mm += 2 * settings.virtual_scene.key_step_mm;
  want.rz_deg -= settings.virtual_scene.key_step_deg;
  expectPose(*f.truth, want, kSamePose);
  expectPose(source->keyOffset(),
             Pose{0, 0, -settings.virtual_scene.key_step_deg, 2 * settings.virtual_scene.key_step_mm, 0, 0}, kSamePose);

  settings.virtual_scene.initial_pose.tz_mm = 1200;
  source->setSettings(settings);
  ASSERT_EQ(source->next(f), Status::Ok);
  EXPECT_EQ(f.index, 2);
  EXPECT_NEAR(f.truth->tz_mm, 1200, 1e-12);
  EXPECT_NEAR(f.truth->tx_mm, want.tx_mm, 1e-12);  // the key offset is kept

  source->resetKeyOffset();
  source->restart();
  EXPECT_EQ(source->nextIndex(), 0);
  ASSERT_EQ(source->next(f), Status::Ok);
  EXPECT_EQ(f.index, 0);
  expectPose(*f.truth, settings.virtual_scene.initial_pose, kSamePose);

  source->setContent(VirtualContent::Pattern);
  ASSERT_EQ(source->next(f), Status::Ok);
  cv::Mat expected;
  renderPattern(settings.camera(), settings.target, settings.pattern, settings.virtual_scene, *f.truth, expected, 1);
  EXPECT_EQ(cv::norm(f.image, expected, cv::NORM_INF), 0.0);
  EXPECT_NE(source->describe().find("pattern"), std::string::npos);
}

// The Virtual source renders through its own camera model, whichever source is in use.
TEST(VirtualSource, RendersThroughItsOwnCamera) {
  Settings settings;
  settings.camera(SourceKind::Virtual).width = 320;
  settings.camera(SourceKind::Virtual).height = 240;
  settings.camera(SourceKind::Virtual).principal_point_px = {159.5, 119.5};
  settings.source = SourceKind::File;  // the File source's 640 x 480 model in use
  auto source = makeVirtualSource(settings);
  Frame f;
  ASSERT_EQ(source->next(f), Status::Ok);
  EXPECT_EQ(f.image.size(), cv::Size(320, 240));
}

// With a set of targets in the settings the Virtual source draws the set's members (here a
// set of one), targets the set knows, not the settings' one "target" (which may belong to none).
TEST(VirtualSource, DrawsTheSetsFirstTarget) {
  Settings settings = virtualSettings();
  TargetSpec first;
  first.id = 4;
  first.geometry.spot_offset_mm = 20.0;
  settings.targets = {first};
  auto source = makeVirtualSource(settings);
  Frame f;
  ASSERT_EQ(source->next(f), Status::Ok);
  cv::Mat expected, lone;
  renderTarget(settings.camera(), first.geometry, settings.virtual_scene, *f.truth, expected, 0);
  renderTarget(settings.camera(), settings.target, settings.virtual_scene, *f.truth, lone, 0);
  EXPECT_EQ(cv::norm(f.image, expected, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(f.image, lone, cv::NORM_INF), 0.0);
}

// With several, every member is drawn, side by side on one body: the second's card 130 mm
// and a 20 mm gap along the first's +X. Every pixel is the first member's scene or the
// second's (the same scene and noise), and the second's card is all there.
TEST(VirtualSource, DrawsEveryMemberOfTheSetSideBySide) {
  Settings settings = virtualSettings();
  settings.virtual_scene.mode = RenderMode::Grey;
  settings.virtual_scene.initial_pose.tz_mm = 1200.0;
  TargetSpec first, second;
  first.id = 1;
  first.geometry.spot_offset_mm = 20.0;
  second.id = 2;
  second.geometry.spot_offset_mm = 30.0;
  settings.targets = {first, second};
  auto source = makeVirtualSource(settings);
  Frame f;
  ASSERT_EQ(source->next(f), Status::Ok);
  ASSERT_TRUE(f.truth);
  const double spacing = settings.virtual_scene.card_size_mm + 20.0;
  const Eigen::Matrix3d R = rotationMatrix(*f.truth);
  const Pose beside = poseFromRt(R, translation(*f.truth) + R * Eigen::Vector3d(spacing, 0.0, 0.0));
  cv::Mat alone, other;
  renderTarget(settings.camera(), first.geometry, settings.virtual_scene, *f.truth, alone, 0);
  renderTarget(settings.camera(), second.geometry, settings.virtual_scene, beside, other, 0);
  int fromOther = 0, neither = 0;
  for (int y = 0; y < f.image.rows; ++y)
    for (int x = 0; x < f.image.cols; ++x) {
      const std::uint8_t g = f.image.at<std::uint8_t>(y, x), a = alone.at<std::uint8_t>(y, x), b = other.at<std::uint8_t>(y, x);
      if (g != a && g == b) ++fromOther;
      if (g != a && g != b) ++neither;
    }
  EXPECT_EQ(neither, 0);
  // The second disk's centre shows its white paper, where the first's frame has none.
  const Eigen::Vector2d c = distortPixel(settings.camera(), projectIdeal(settings.camera(), translation(beside)));
  const Eigen::Vector2d e = distortPixel(settings.camera(), projectIdeal(
      settings.camera(), translation(beside) + R * Eigen::Vector3d(0.8 * second.geometry.radius_mm, 0.0, 0.0)));
  ASSERT_TRUE(c.x() > 0 && c.x() < f.image.cols - 1 && c.y() > 0 && c.y() < f.image.rows - 1);
  const cv::Point centre(static_cast<int>(std::lround(e.x())), static_cast<int>(std::lround(e.y())));
  EXPECT_EQ(f.image.at<std::uint8_t>(centre), other.at<std::uint8_t>(centre));
  EXPECT_NE(f.image.at<std::uint8_t>(centre), alone.at<std::uint8_t>(centre));
  // The card's area: some thousands of pixels at 1.2 m.
  EXPECT_GT(fromOther, 2000);
}

TEST(VirtualSource, KeysFromAnotherThreadWhileRendering) {
  Settings settings = virtualSettings();
  settings.virtual_scene.motion.kind = MotionKind::Static;
  settings.virtual_scene.mode = RenderMode::Grey;
  auto source = makeVirtualSource(settings);
  std::atomic<bool> done{false};
  std::thread gui([&] {
    for (int i = 0; i < 200; ++i) {
      source->pressKey(i % 2 ? VirtualKey::TyPlus : VirtualKey::TxPlus);
      if (i % 50 == 0) source->setSettings(settings);
    }
    done = true;
  });
  Frame f;
  double last_sum = -1;
  while (!done) {
    ASSERT_EQ(source->next(f), Status::Ok);
    const double sum = f.truth->tx_mm + f.truth->ty_mm;
    EXPECT_GE(sum, last_sum);  // offsets only grow
    last_sum = sum;
  }
  gui.join();
  ASSERT_EQ(source->next(f), Status::Ok);
  EXPECT_NEAR(f.truth->tx_mm, 100 * settings.virtual_scene.key_step_mm, 1e-9);
  EXPECT_NEAR(f.truth->ty_mm, 100 * settings.virtual_scene.key_step_mm, 1e-9);
}

}  // namespace
}  // namespace imagepro

namespace imagepro {
namespace {

// data/samples holds frames rendered by tools/make-samples.sh; they must stay readable,
// listed in truth.csv, and reproducible by the renderer.
TEST(Samples, ReadableListedAndReproducible) {
  const std::string dir = std::string(IMAGEPRO_DATA_DIR) + "/samples";
  std::vector<std::string> paths;
  std::string error;
  ASSERT_EQ(listImageSequence(dir, paths, error), Status::Ok) << error;
  ASSERT_GE(paths.size(), 6u);
  std::string truth;
  {
    std::ifstream in(dir + "/truth.csv");
    truth.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_EQ(truth.rfind("frame,status,Rx_deg,Ry_deg,Rz_deg,Tx_mm,Ty_mm,Tz_mm", 0), 0u);
  auto files = makeFileSource(paths);
  Frame f;
  for (size_t i = 0; i < paths.size(); ++i) {
    ASSERT_EQ(files->next(f), Status::Ok) << files->lastError();
    EXPECT_EQ(f.image.size(), cv::Size(640, 480));
    EXPECT_NE(truth.find("\n" + f.name + ",ok,"), std::string::npos) << f.name;
  }
  EXPECT_EQ(files->next(f), Status::EndOfStream);

  // The facing sample is the shipped settings' grey scene at its pose, pixel for pixel.
  Settings settings;
  ASSERT_EQ(loadSettings(std::string(IMAGEPRO_DATA_DIR) + "/settings.json", settings, error), Status::Ok) << error;
  settings.virtual_scene.mode = RenderMode::Grey;
  settings.virtual_scene.backdrop = Backdrop::Plain;  // as tools/make-samples.sh renders it
  cv::Mat rendered, stored;
  renderTarget(settings.camera(), settings.target, settings.virtual_scene, Pose{0, 0, 0, 0, 0, 800}, rendered);
  ASSERT_EQ(readGreyImage(dir + "/sample01_facing.png", stored, error), Status::Ok) << error;
  EXPECT_EQ(cv::norm(rendered, stored, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace imagepro
