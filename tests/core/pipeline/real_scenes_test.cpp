// The default pipeline judged on real scenes: the target drawn over
// photographs with uneven light, blur, motion blur, noise and JPEG (core/source/
// real_scene.h), negatives without it, and a video in which it hides for 12 frames.
// The figures are printed; the thresholds are what the pipeline achieved when this
// test was written (docs/accuracy.md, "Real scenes"), so a change that loses ground
// fails, and one that gains it should raise them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/pipeline/engine.h"
#include "core/source/real_scene_video.h"

namespace imagepro {
namespace {

constexpr std::uint64_t kSeed = 1;
constexpr int kStills = 120;
constexpr int kNegatives = 30;
constexpr int kVideoFrames = 150;

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double at = p * (v.size() - 1);
  const auto lo = static_cast<std::size_t>(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - lo) * (v[hi] - v[lo]);
}

// What one set of frames with a target came to.
struct Figures {
  int frames = 0, posed = 0, correct = 0, wrong = 0;
  std::vector<double> rotation_deg, position_percent;
  std::map<std::string, int> statuses;

  void add(const FrameResult& r, const Pose& truth) {
    ++frames;
    ++statuses[std::string(statusName(r.status))];
    if (r.status != Status::Ok || !r.pose) return;
    ++posed;
    const double rotation = rotationAngleBetweenDeg(rotationMatrix(truth), rotationMatrix(*r.pose));
    rotation_deg.push_back(rotation);
    position_percent.push_back(100.0 * (translation(*r.pose) - translation(truth)).norm() / translation(truth).norm());
    (rotation <= 5.0 ? correct : wrong)++;
  }

  void print(const char* what) const {
    std::printf("%-7s frames %3d | with a pose %3d (%5.1f %%) | correct (<= 5 deg) %3d (%5.1f %%) | off by > 5 deg %2d | "
                "rotation median %.3f p95 %.2f deg | position median %.3f p95 %.2f %% of the distance\n",
                what, frames, posed, 100.0 * posed / frames, correct, 100.0 * correct / frames, wrong,
                percentile(rotation_deg, 0.5), percentile(rotation_deg, 0.95), percentile(position_percent, 0.5),
                percentile(position_percent, 0.95));
    std::printf("%-7s statuses:", what);
    for (const auto& [name, n] : statuses) std::printf(" %s %d", name.c_str(), n);
    std::printf("\n");
  }
};

Settings defaults() {
  Settings s;
  std::string error;
  EXPECT_EQ(loadSettings(std::string(IMAGEPRO_DATA_DIR) + "/settings.json", s, error), Status::Ok) << error;
  return s;
}

Frame asFrame(const RealSceneFrame& f, int index, const char* stem) {
  Frame frame;
  frame.image = f.image;
  frame.index = index;
  frame.name = std::string(stem) + std::to_string(index) + ".png";
  frame.truth = f.truth;
  return frame;
}

TEST(RealScenes, DefaultPipelineOnPhotographs) {
  const std::string dir = defaultBackgroundsDir();
  std::vector<std::string> photos = listBackgrounds(dir);
  if (photos.empty())
    GTEST_SKIP() << "no photographs in " << dir << ": install Debian's opencv-doc (tools/setup.sh does) or set "
                 << "IMAGEPRO_BACKGROUNDS to a folder of JPEG/PNG photographs";
  const Settings settings = defaults();
  const RealScenes scenes(settings, std::move(photos));
  std::string error;

  // Stills and negatives, as `render --scene real --frames 120 --negatives 30 --seed 1` writes them.
  Figures stills;
  int false_detections = 0;
  Engine engine(settings);
  for (int i = 0; i < kStills + kNegatives; ++i) {
    RealSceneFrame f;
    ASSERT_TRUE(scenes.still(kSeed, i, i < kStills, f, error)) << error;
    engine.resetTracking();  // unrelated stills
    FrameResult r;
    engine.process(asFrame(f, i, i < kStills ? "frame_" : "negative_"), r);
    if (f.truth)
      stills.add(r, *f.truth);
    else
      false_detections += r.status == Status::Ok && r.pose.has_value();
  }

  // The video, tracked from frame to frame as a camera's would be.
  const RealSceneVideo video(scenes, kSeed, kVideoFrames);
  Figures visible;
  int found_in_hiding = 0, reacquired_after = -1;
  Engine tracker(settings);
  for (int i = 0; i < video.frames(); ++i) {
    RealSceneFrame f;
    ASSERT_TRUE(video.frame(i, f, error)) << error;
    Frame frame = asFrame(f, i, "video_");
    frame.name.clear();  // a stream, not files
    frame.timestamp_s = i / RealSceneVideo::kFrameRateHz;
    FrameResult r;
    tracker.process(frame, r);
    if (!f.truth) {
      found_in_hiding += r.status == Status::Ok && r.pose.has_value();
      continue;
    }
    const int correct_before = visible.correct;
    visible.add(r, *f.truth);
    if (i >= video.hiddenEnd() && reacquired_after < 0 && visible.correct > correct_before)
      reacquired_after = i - video.hiddenEnd();
  }

  std::printf("Real scenes (seed %d, photographs of %s):\n", static_cast<int>(kSeed), dir.c_str());
  stills.print("stills");
  std::printf("negatives %d | false detections %d\n", kNegatives, false_detections);
  visible.print("video");
  std::printf("video: %d hidden frames, a pose in %d of them; first correct pose %d frames after the target "
              "reappears (-1: never)\n",
              video.hiddenEnd() - video.hiddenBegin(), found_in_hiding, reacquired_after);

  // Measured by this test (accuracy.md gives the larger study): stills 117 of 120 posed, 116 correct,
  // 1 off by more than 5 deg (5.4 deg, a pose halfway between two close circles), 2 AmbiguousPose
  // (far targets near head-on; 5 before halfway poses, 8 with a fixed 0.15 px margin), rotation
  // median 0.174 deg, p95 0.78 deg, position median 0.039 %; no false detection in
  // 30 negatives; video 138 of 138 visible frames correct (rotation median 0.055 deg), none in
  // hiding, found again on the frame it reappears. Without
  // the rim edge model the stills' medians were 0.245 deg and 0.11 %, their p95 1.97 deg.
  // (With the thesis's global threshold alone: 44 correct stills, 66 video frames.) The
  // floors leave a few frames for OpenCV's filters rounding differently on other
  // processors (a grey level here and there moves a borderline frame).
  EXPECT_GE(stills.correct, 112);
  EXPECT_LE(stills.wrong, 3);
  EXPECT_LE(percentile(stills.rotation_deg, 0.5), 0.2);
  EXPECT_LE(percentile(stills.rotation_deg, 0.95), 1.5);
  EXPECT_LE(percentile(stills.position_percent, 0.5), 0.07);
  EXPECT_EQ(false_detections, 0);
  EXPECT_GE(visible.correct, 134);
  EXPECT_LE(visible.wrong, 1);
  EXPECT_LE(percentile(visible.rotation_deg, 0.5), 0.1);
  EXPECT_EQ(found_in_hiding, 0);
  EXPECT_GE(reacquired_after, 0);
  EXPECT_LE(reacquired_after, 3);
}

// Webcam stills (1280 x 720, f = 1000 px, the rig's occluders, glare and dim light, as
// `render --scene real --webcam --seed 11 / 12` draws them) that only the narrow local
// pass at the frame's scale (29 px, stage_chain.h) finds: far targets, 1.9-2.4 m, most on
// dim paper (grey 71-93) before a brighter scene, whose disk is darker than the wide
// window's mean and whose blurred spots the 15 px window cuts into the card. Before that
// pass none of them was posed correctly (SpotsNotFound, NoTarget, one off by 23 deg).
TEST(RealScenes, FarDimWebcamTargetsAreFoundByTheNarrowWindowAtTheFramesScale) {
  std::vector<std::string> photos = listBackgrounds(defaultBackgroundsDir());
  if (photos.empty()) GTEST_SKIP() << "no photographs in " << defaultBackgroundsDir();
  Settings webcam;
  std::string error;
  ASSERT_EQ(loadSettings(std::string(IMAGEPRO_DATA_DIR) + "/webcam-1280x720.json", webcam, error), Status::Ok)
      << error;
  webcam.pipeline.tracking.mode = TrackingMode::Off;
  const RealScenes rigged(webcam, std::move(photos), kWebcamRigEffects);
  Engine engine(webcam);
  const struct {
    std::uint64_t seed;
    int index;
  } stills[] = {{11, 56}, {11, 86}, {11, 106}, {11, 132}, {12, 52}, {12, 57}, {12, 152}, {12, 374}};
  int correct = 0;
  for (const auto& [seed, index] : stills) {
    RealSceneFrame f;
    ASSERT_TRUE(rigged.still(seed, index, true, f, error)) << error;
    ASSERT_TRUE(f.truth.has_value());
    FrameResult r;
    engine.process(asFrame(f, index, "frame_"), r);
    const bool right = r.status == Status::Ok && r.pose &&
                       rotationAngleBetweenDeg(rotationMatrix(*f.truth), rotationMatrix(*r.pose)) <= 5.0;
    std::printf("seed %d still %d: %s%s\n", static_cast<int>(seed), index, statusName(r.status).data(),
                right ? ", correct" : "");
    correct += right;
  }
  // All eight on this machine; one left for another processor's rounding (see above).
  EXPECT_GE(correct, 7);
}

}  // namespace
}  // namespace imagepro
