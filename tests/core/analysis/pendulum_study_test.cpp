// The pendulum study's driver (thesis 5.3.2) against the virtual pendulum's own length,
// period and g; its re-timing of frames without times; the frame limit; cancellation,
// progress, and a source whose frames cannot be read.
#include <gtest/gtest.h>

#include <vector>

#include "core/analysis/frame_limit.h"
#include "core/analysis/pendulum_study.h"
#include "core/source/virtual_motion.h"

namespace imagepro {
namespace {

Settings pendulumSettings() {
  Settings s;
  s.virtual_scene.mode = RenderMode::Grey;
  s.virtual_scene.frame_rate_hz = 25.0;
  s.virtual_scene.motion.kind = MotionKind::Pendulum;
  return s;
}

// The frames of `first` (if any), then `count` frames that fail to be read, each named.
class ThenMissingFiles final : public FrameSource {
 public:
  ThenMissingFiles(FrameSource* first, int count) : first_(first), left_(count) {}
  Status next(Frame& out) override {
    if (first_ && first_->next(out) != Status::EndOfStream) return Status::Ok;
    first_ = nullptr;
    if (left_-- <= 0) return Status::EndOfStream;
    out.name = "swing" + std::to_string(++missing_) + ".png";
    error_ = out.name + ": no such file";
    return Status::FileNotFound;
  }
  std::string lastError() const override { return error_; }
  double frameRateHz() const override { return 0.0; }
  std::string describe() const override { return "missing files"; }

 private:
  FrameSource* first_;
  int left_;
  int missing_ = 0;
  std::string error_;
};

TEST(PendulumStudy, VirtualPendulumGivesItsOwnLengthPeriodAndG) {
  VirtualPendulumParams params;
  params.frames = 150;
  int done = 0, total = 0, sunk = 0;
  const StudyCallbacks callbacks{[&](int d, int t) {
                                   done = d;
                                   total = t;
                                 },
                                 {}};
  const PendulumStudyResult r =
      runVirtualPendulum(pendulumSettings(), params, callbacks, [&](const FrameResult&) { ++sunk; });
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  EXPECT_EQ(done, 150);
  EXPECT_EQ(total, 150);
  EXPECT_EQ(sunk, 150);
  ASSERT_EQ(r.samples.size(), 150u);
  EXPECT_TRUE(r.unreadable.empty());
  // Frame i at i / 25 s: the virtual source's own times.
  EXPECT_DOUBLE_EQ(r.samples[25].t_s, 1.0);
  ASSERT_TRUE(r.has_truth);
  const PendulumOptions& truth = pendulumSettings().virtual_scene.pendulum;
  EXPECT_DOUBLE_EQ(r.truth.period_s, pendulumPeriodS(truth));
  EXPECT_EQ(r.analysis.valid_frames, 150);
  EXPECT_NEAR(r.analysis.length_mm, truth.length_mm, 0.003 * truth.length_mm);
  EXPECT_NEAR(r.analysis.period_s, r.truth.period_s, 0.002 * r.truth.period_s);
  EXPECT_NEAR(r.analysis.g_m_s2, truth.gravity_m_s2, 0.01 * truth.gravity_m_s2);
}

TEST(PendulumStudy, RateSetsTheVirtualFrameTimes) {
  VirtualPendulumParams params;
  params.frames = 3;
  params.rate_hz = 50.0;
  const PendulumStudyResult r = runVirtualPendulum(pendulumSettings(), params, {});
  ASSERT_EQ(r.samples.size(), 3u);
  EXPECT_DOUBLE_EQ(r.samples[2].t_s, 0.04);
  EXPECT_EQ(r.status, Status::TooFewFrames);  // three frames cannot give a swing
}

TEST(PendulumStudy, CancelStopsBeforeTheNextFrame) {
  VirtualPendulumParams params;
  int done = 0;
  const StudyCallbacks callbacks{[&](int d, int) { done = d; }, [&] { return done >= 5; }};
  const PendulumStudyResult r = runVirtualPendulum(pendulumSettings(), params, callbacks);
  EXPECT_EQ(r.status, Status::Stopped);
  EXPECT_EQ(r.samples.size(), 5u);
}

TEST(PendulumStudy, UnreadableFramesAreNamedWithTheirReason) {
  ThenMissingFiles missing(nullptr, 3);
  PendulumStudyResult r = runPendulumSource(missing, pendulumSettings(), 25.0, true, {});
  EXPECT_EQ(r.status, Status::FileNotFound);
  ASSERT_EQ(r.unreadable.size(), 3u);
  EXPECT_EQ(r.unreadable[0], "swing1.png: no such file");
  EXPECT_EQ(r.error, "FileNotFound: swing1.png: no such file (and 2 more frames that could not be read)");

  // Some frames read, too few with a pose: the analysis's reason, then the first unreadable frame's.
  PendulumSource pendulum(pendulumSettings(), MotionBlur{});
  FrameLimit four(pendulum, 4);
  ThenMissingFiles some(&four, 2);
  r = runPendulumSource(some, pendulumSettings(), 25.0, true, {});
  EXPECT_EQ(r.status, Status::TooFewFrames);
  EXPECT_EQ(r.unreadable.size(), 2u);
  EXPECT_NE(r.error.find("(4 of 6 frames with a pose); 2 of them could not be read, the first: swing1.png: no such file"),
            std::string::npos)
      << r.error;
}

TEST(PendulumStudy, FramesWithoutTimesAreTimedByTheRate) {
  std::vector<PoseSample> samples(4);
  const std::vector<std::int64_t> indices = {0, 1, 3, 4};  // frame 2 was skipped
  EXPECT_FALSE(retimeSamples(samples, indices, 0.0));
  ASSERT_TRUE(retimeSamples(samples, indices, 10.0));
  EXPECT_DOUBLE_EQ(samples[2].t_s, 0.3);
  EXPECT_DOUBLE_EQ(samples[3].t_s, 0.4);
  // Times that increase are the frames' own.
  samples[0].t_s = 5.0;
  samples[1].t_s = 6.0;
  samples[2].t_s = 6.5;
  samples[3].t_s = 9.0;
  ASSERT_TRUE(retimeSamples(samples, indices, 10.0));
  EXPECT_DOUBLE_EQ(samples[2].t_s, 6.5);
}

TEST(PendulumStudy, FrameLimitEndsAnEndlessSource) {
  PendulumSource pendulum(pendulumSettings(), MotionBlur{});
  FrameLimit limited(pendulum, 2);
  Frame f;
  EXPECT_EQ(limited.next(f), Status::Ok);
  EXPECT_EQ(limited.next(f), Status::Ok);
  EXPECT_EQ(limited.next(f), Status::EndOfStream);
  EXPECT_EQ(limited.next(f), Status::EndOfStream);
  EXPECT_EQ(limited.describe(), pendulum.describe());
}

}  // namespace
}  // namespace imagepro
