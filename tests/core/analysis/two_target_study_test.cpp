// The two-target study's driver (thesis 5.3.1) against the object's known distance and
// angle: the virtual run at a study position, the same frames read from a frame source
// (one of them unreadable), progress up to the total, and cancellation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/analysis/two_target_study.h"

namespace imagepro {
namespace {

// Frames handed out in turn; an empty image stands for a frame that cannot be read.
class ListSource final : public FrameSource {
 public:
  explicit ListSource(std::vector<cv::Mat> images) : images_(std::move(images)) {}
  Status next(Frame& out) override {
    if (next_ >= images_.size()) return Status::EndOfStream;
    out.index = static_cast<std::int64_t>(next_);
    out.name = "frame" + std::to_string(next_) + ".png";
    out.image = images_[next_++];
    if (!out.image.empty()) return Status::Ok;
    error_ = out.name + ": cannot be decoded";
    return Status::FileUnreadable;
  }
  std::string lastError() const override { return error_; }
  double frameRateHz() const override { return 0.0; }
  std::string describe() const override { return "list"; }

 private:
  std::vector<cv::Mat> images_;
  std::size_t next_ = 0;
  std::string error_;
};

Settings studySettings() {
  Settings s;
  s.virtual_scene.mode = RenderMode::Grey;
  return s;
}

struct Progress {
  int calls = 0, done = -1, total = -1;
  StudyCallbacks callbacks(std::function<bool()> cancelled = {}) {
    return {[this](int d, int t) {
              ++calls;
              done = d;
              total = t;
            },
            std::move(cancelled)};
  }
};

TEST(TwoTargetStudy, VirtualRunMeasuresTheKnownDistanceAndAngle) {
  VirtualTwoTargetParams params;
  params.position = 2;
  params.frames_per_position = 4;
  Progress progress;
  const TwoTargetStudyResult r = runVirtualTwoTargets(studySettings(), params, progress.callbacks());
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  ASSERT_EQ(r.frames.size(), 4u);
  EXPECT_EQ(progress.done, 4);
  EXPECT_EQ(progress.total, 4);
  EXPECT_EQ(progress.calls, 5);  // the total first, then after every frame
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const TwoTargetFrame& f = r.frames[i];
    EXPECT_EQ(f.position, 2);
    ASSERT_TRUE(f.lighting);
    EXPECT_EQ(*f.lighting, i < 2 ? StudyLighting::Natural : StudyLighting::Extra);
    ASSERT_EQ(f.status[0], Status::Ok);
    EXPECT_NEAR(f.measurement[0].distance_mm, params.object.spacing_mm, 0.5);
    EXPECT_NEAR(f.measurement[0].angle_deg, params.object.angle_deg, 0.5);
  }
  // One summary per correction, the corrected one first, over every frame.
  ASSERT_EQ(r.summaries.size(), 2u);
  EXPECT_TRUE(r.summaries[0].correction);
  EXPECT_FALSE(r.summaries[1].correction);
  EXPECT_EQ(r.summaries[0].distance_mm.samples, 4);
  EXPECT_LT(r.summaries[0].distance_mm.max_abs, 0.5);
  EXPECT_LT(r.summaries[0].angle_deg.max_abs, 0.5);
  // Without correction the thesis lens bends the normals apart.
  EXPECT_GT(r.summaries[1].angle_deg.mean, std::abs(r.summaries[0].angle_deg.mean));
}

TEST(TwoTargetStudy, AllPositionsInTurnAndAnObjectThatDoesNotFit) {
  VirtualTwoTargetParams params;
  params.frames_per_position = 2;
  const TwoTargetStudyResult r = runVirtualTwoTargets(studySettings(), params, {});
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  ASSERT_EQ(r.frames.size(), 6u);
  ASSERT_EQ(r.summaries.size(), 6u);
  for (int p = 0; p < 3; ++p) EXPECT_EQ(r.summaries[2 * p].position, p + 1);
  params.object.spacing_mm = 20.0;  // the 130 mm cards overlap the edge
  EXPECT_EQ(runVirtualTwoTargets(studySettings(), params, {}).status, Status::InvalidSettings);
}

TEST(TwoTargetStudy, CancelStopsBeforeTheNextFrame) {
  VirtualTwoTargetParams params;
  params.frames_per_position = 10;
  Progress progress;
  const TwoTargetStudyResult r =
      runVirtualTwoTargets(studySettings(), params, progress.callbacks([&] { return progress.done >= 2; }));
  EXPECT_EQ(r.status, Status::Stopped);
  EXPECT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(progress.total, 30);
}

TEST(TwoTargetStudy, SourceFramesAreMeasuredAndUnreadableOnesKeepTheirReason) {
  Settings s = studySettings();
  s.camera().distortion = kThesisCameraDistortion;
  const TwoTargetObject object;
  TwoTargetRenderWorkspace ws;
  std::vector<cv::Mat> images(3);
  for (int i : {0, 2})
    renderTwoTargets(s.camera(), s.target, s.virtual_scene, object, twoTargetStudyPosition(1), images[i],
                     static_cast<std::uint64_t>(i), ws);
  ListSource source(images);
  Progress progress;
  const TwoTargetStudyResult r = runTwoTargetSource(source, s, object, progress.callbacks());
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(progress.done, 3);
  EXPECT_EQ(progress.total, 0);  // a source's length is not known
  EXPECT_EQ(r.frames[1].status[0], Status::FileUnreadable);
  EXPECT_EQ(r.frames[1].error, "frame1.png: cannot be decoded");
  EXPECT_FALSE(r.frames[0].lighting);
  for (int i : {0, 2}) {
    EXPECT_EQ(r.frames[i].name, "frame" + std::to_string(i) + ".png");
    ASSERT_EQ(r.frames[i].status[0], Status::Ok);
    EXPECT_NEAR(r.frames[i].measurement[0].distance_mm, object.spacing_mm, 0.5);
    EXPECT_NEAR(r.frames[i].measurement[0].angle_deg, object.angle_deg, 0.5);
  }
  ASSERT_EQ(r.summaries.size(), 2u);
  EXPECT_EQ(r.summaries[0].frames, 3);
  EXPECT_EQ(r.summaries[0].distance_mm.samples, 2);
  ASSERT_FALSE(r.failures.empty());
  EXPECT_EQ(r.failures.front(), std::make_pair(Status::FileUnreadable, 2));  // both corrections
}

}  // namespace
}  // namespace imagepro
