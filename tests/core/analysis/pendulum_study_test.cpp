// The pendulum study's driver (thesis 5.3.2) against the virtual pendulum's own length,
// period and g; its re-timing of frames without times; the frame limit; cancellation,
// progress, and a source whose frames cannot be read.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "core/analysis/frame_limit.h"
#include "core/analysis/pendulum_study.h"
#include "core/pipeline/data_out.h"
#include "core/source/virtual_motion.h"
#include "support/test_dirs.h"

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
  PendulumStudyResult r = runPendulumSource(missing, pendulumSettings(), 25.0, {}, {});
  EXPECT_EQ(r.status, Status::FileNotFound);
  ASSERT_EQ(r.unreadable.size(), 3u);
  EXPECT_EQ(r.unreadable[0], "swing1.png: no such file");
  EXPECT_EQ(r.error, "FileNotFound: swing1.png: no such file (and 2 more frames that could not be read)");

  // Some frames read, too few with a pose: the analysis's reason, then the first unreadable frame's.
  PendulumSource pendulum(pendulumSettings(), MotionBlur{});
  FrameLimit four(pendulum, 4);
  ThenMissingFiles some(&four, 2);
  r = runPendulumSource(some, pendulumSettings(), 25.0, {}, {});
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

// As the thesis ran it: the length from the pendulum held still at five places, the
// period from a swing too small to fix the sphere.
TEST(PendulumStudy, VirtualStillAndSwingRecordingsGiveKnownG) {
  Settings s = pendulumSettings();
  s.virtual_scene.pendulum.amplitude_deg = 4.0;
  VirtualPendulumParams params;
  params.still_recording = true;
  params.still.positions = 5;
  int done = 0, total = 0, sunk = 0;
  const StudyCallbacks callbacks{[&](int d, int t) {
                                   done = d;
                                   total = t;
                                 },
                                 {}};
  const PendulumStudyResult r = runVirtualPendulum(s, params, callbacks, [&](const FrameResult&) { ++sunk; });
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  EXPECT_EQ(done, 275);
  EXPECT_EQ(total, 275);
  EXPECT_EQ(sunk, 250);  // data out is the swing's
  ASSERT_TRUE(r.has_still);
  EXPECT_EQ(r.still_samples.size(), 25u);
  EXPECT_TRUE(r.analysis.length_from_still);
  EXPECT_EQ(r.analysis.still_valid_frames, 25);
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  EXPECT_NEAR(r.analysis.length_mm, truth.length_mm, 0.002 * truth.length_mm);
  EXPECT_NEAR(r.analysis.g_m_s2, truth.gravity_m_s2, 0.005 * truth.gravity_m_s2);
  // The swing alone cannot fix the length nearly as well.
  params.still_recording = false;
  const PendulumStudyResult alone = runVirtualPendulum(s, params, {});
  ASSERT_EQ(alone.status, Status::Ok) << alone.error;
  EXPECT_GT(alone.analysis.length_sigma_mm, 3.0 * r.analysis.length_sigma_mm);
}

// Interlaced frames (thesis fig. 5.11): a wide swing combs the target's outline past
// recognition in most frames, as the thesis found; a small one is found in every frame
// and gives the period, with the length from the pendulum held still.
TEST(PendulumStudy, InterlacedFrames) {
  Settings s = pendulumSettings();
  VirtualPendulumParams params;
  params.interlaced = true;
  params.frames = 100;
  PendulumStudyResult r = runVirtualPendulum(s, params, {});
  EXPECT_EQ(r.status, Status::TargetLost) << r.error;
  EXPECT_LT(r.analysis.valid_frames, 50);

  s.virtual_scene.pendulum.amplitude_deg = 6.0;
  params.frames = 250;
  params.still_recording = true;
  r = runVirtualPendulum(s, params, {});
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  EXPECT_EQ(r.analysis.valid_frames, 250);
  EXPECT_NEAR(r.analysis.period_s, r.truth.period_s, 1e-4 * r.truth.period_s);
  EXPECT_NEAR(r.analysis.length_mm, r.truth.length_mm, 0.002 * r.truth.length_mm);
  EXPECT_NEAR(r.analysis.g_m_s2, r.truth.g_m_s2, 0.005 * r.truth.g_m_s2);
}

void writePoses(const std::string& path, const std::vector<Pose>& poses, double rate_hz) {
  std::filesystem::remove(path);
  DataOut out;
  std::string error;
  ASSERT_EQ(out.open(path, ExistingFile::Fail, error), Status::Ok) << error;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    FrameResult r;
    r.index = static_cast<std::int64_t>(i);
    r.timestamp_s = static_cast<double>(i) / rate_hz;
    r.status = Status::Ok;
    r.pose = poses[i];
    ASSERT_TRUE(out.write(r, error)) << error;
  }
  out.close();
}

TEST(PendulumStudy, StillAndSwingFromRecordedFiles) {
  const std::filesystem::path dir = test::freshDir("pendulum_still_swing");
  const Settings settings = pendulumSettings();
  const VirtualSceneOptions& scene = settings.virtual_scene;
  std::vector<Pose> still, swing;
  for (double angle : {-25.0, -12.0, 0.0, 12.0, 25.0}) still.push_back(pendulumPoseAtAngle(scene, angle));
  for (int i = 0; i < 200; ++i) swing.push_back(virtualPoseAt(scene, i / 25.0));
  const std::string still_csv = (dir / "still.csv").string(), swing_csv = (dir / "swing.csv").string();
  writePoses(still_csv, still, 25.0);
  writePoses(swing_csv, swing, 25.0);
  PendulumStudyResult r = runPendulumStillSwing(still_csv, swing_csv, settings, 25.0, {}, {});
  ASSERT_EQ(r.status, Status::Ok) << r.error;
  EXPECT_EQ(r.analysis.still_frames, 5);
  EXPECT_NEAR(r.analysis.length_mm, scene.pendulum.length_mm, 0.01);
  EXPECT_NEAR(r.analysis.g_m_s2, scene.pendulum.gravity_m_s2, 0.001);

  // Each recording's problem is named as its own.
  r = runPendulumStillSwing((dir / "none.csv").string(), swing_csv, settings, 25.0, {}, {});
  EXPECT_EQ(r.status, Status::FileNotFound);
  EXPECT_EQ(r.error.rfind("still: FileNotFound", 0), 0u) << r.error;
  r = runPendulumStillSwing(still_csv, (dir / "none").string(), settings, 25.0, {}, {});
  EXPECT_NE(r.status, Status::Ok);
  EXPECT_EQ(r.error.rfind("swing: ", 0), 0u) << r.error;
  writePoses(still_csv, {still[0], still[4]}, 25.0);
  r = runPendulumStillSwing(still_csv, swing_csv, settings, 25.0, {}, {});
  EXPECT_EQ(r.status, Status::TooFewFrames);
  EXPECT_EQ(r.error.rfind("still: TooFewFrames", 0), 0u) << r.error;
}

TEST(PendulumStudy, RunsSummaryGivesMeanAndSpread) {
  std::vector<PendulumAnalysis> runs(3);
  const double g[3] = {9.785, 9.757, 9.788};
  for (int i = 0; i < 3; ++i) {
    runs[i].length_mm = 443.0 + i;
    runs[i].period_s = 1.338;
    runs[i].g_m_s2 = g[i];
    runs[i].g_uncorrected_m_s2 = g[i] - 0.1;
  }
  const PendulumRunsSummary s = summarizePendulumRuns(runs);
  EXPECT_EQ(s.runs, 3);
  EXPECT_DOUBLE_EQ(s.length_mm, 444.0);
  EXPECT_DOUBLE_EQ(s.length_sd_mm, 1.0);
  EXPECT_DOUBLE_EQ(s.period_sd_s, 0.0);
  EXPECT_NEAR(s.g_m_s2, (9.785 + 9.757 + 9.788) / 3, 1e-12);
  EXPECT_NEAR(s.g_sd_m_s2, 0.017097, 1e-6);
  EXPECT_NEAR(s.g_uncorrected_m_s2, s.g_m_s2 - 0.1, 1e-12);
  EXPECT_EQ(summarizePendulumRuns({}).runs, 0);
  EXPECT_DOUBLE_EQ(summarizePendulumRuns(std::span(runs).first(1)).g_sd_m_s2, 0.0);
}

}  // namespace
}  // namespace imagepro
