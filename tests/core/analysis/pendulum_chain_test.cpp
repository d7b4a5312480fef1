// The whole g study on the virtual pendulum: rendered grey and noisy at 25 frames/s,
// reconstructed by the engine frame by frame, analysed (thesis 5.3.2). The goals:
// length within 0.2 % and g within 0.5 % of the scene's.
#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/pendulum.h"
#include "core/analysis/pendulum_scene.h"
#include "core/pipeline/engine.h"
#include "core/source/virtual_motion.h"

namespace imagepro {
namespace {

Settings noisyPendulum() {
  Settings s;
  s.virtual_scene.mode = RenderMode::Grey;
  s.virtual_scene.noise_sigma = 3.0;
  s.virtual_scene.frame_rate_hz = 25.0;
  s.virtual_scene.motion.kind = MotionKind::Pendulum;
  return s;
}

std::vector<PoseSample> reconstructSequence(const Settings& s, const MotionBlur& blur, int frames, int* truth_misses) {
  PendulumSource source(s, blur);
  Engine engine(s);
  FrameResult r;
  std::vector<PoseSample> out;
  for (int i = 0; i < frames; ++i) {
    engine.step(source, r);
    PoseSample p;
    p.t_s = r.timestamp_s;
    p.valid = ok(r.status) && r.pose.has_value();
    if (p.valid) p.pose = *r.pose;
    if (p.valid && r.truth && (translation(*r.pose) - translation(*r.truth)).norm() > 2.0) ++*truth_misses;
    out.push_back(p);
  }
  return out;
}

TEST(PendulumChain, VirtualPendulumGivesLengthAndGravity) {
  const Settings s = noisyPendulum();
  int misses = 0;
  const std::vector<PoseSample> seq = reconstructSequence(s, {}, 250, &misses);
  EXPECT_EQ(misses, 0);
  PendulumAnalysis a;
  ASSERT_EQ(analyzePendulum(seq, {}, a), Status::Ok);
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  EXPECT_EQ(a.valid_frames, 250);
  EXPECT_NEAR(a.length_mm, truth.length_mm, 0.002 * truth.length_mm);
  EXPECT_NEAR(a.g_m_s2, truth.gravity_m_s2, 0.005 * truth.gravity_m_s2);
  EXPECT_NEAR(a.period_s, pendulumPeriodS(truth), 0.001 * pendulumPeriodS(truth));
  EXPECT_NEAR(a.amplitude_deg, truth.amplitude_deg, 0.2);
  const Eigen::Vector3d pivot(truth.pivot_mm[0], truth.pivot_mm[1], truth.pivot_mm[2]);
  EXPECT_LT((a.sphere.centre_mm - pivot).norm(), 3.0);
  // The reported uncertainties cover the errors.
  EXPECT_LT(std::abs(a.length_mm - truth.length_mm), 4.0 * a.length_sigma_mm + 0.1);
  EXPECT_GT(a.length_sigma_mm, 0.0);
  EXPECT_GT(a.g_sigma_m_s2, 0.0);
}

TEST(PendulumChain, MotionBlurredFrames) {
  // A 12 ms exposure smears the target by up to 6 px at the bottom of the swing.
  const Settings s = noisyPendulum();
  int misses = 0;
  const std::vector<PoseSample> seq = reconstructSequence(s, MotionBlur{0.012, 4}, 200, &misses);
  EXPECT_EQ(misses, 0);
  PendulumAnalysis a;
  ASSERT_EQ(analyzePendulum(seq, {}, a), Status::Ok);
  const PendulumOptions& truth = s.virtual_scene.pendulum;
  EXPECT_NEAR(a.length_mm, truth.length_mm, 0.004 * truth.length_mm);
  EXPECT_NEAR(a.g_m_s2, truth.gravity_m_s2, 0.01 * truth.gravity_m_s2);
}

TEST(PendulumScene, BlurAveragesTheInstantsOfTheExposure) {
  Settings s = noisyPendulum();
  s.virtual_scene.noise_sigma = 0.0;
  PendulumRenderWorkspace ws;
  cv::Mat sharp, blurred, a, b;
  renderPendulumFrame(s, 0.0, {}, false, 0, sharp, ws);
  renderPendulumFrame(s, 0.0, MotionBlur{0.02, 2}, false, 0, blurred, ws);
  renderPendulumFrame(s, -0.005, {}, false, 0, a, ws);
  renderPendulumFrame(s, 0.005, {}, false, 0, b, ws);
  cv::Mat mean;
  cv::addWeighted(a, 0.5, b, 0.5, 0.0, mean, CV_32F);
  mean.convertTo(mean, CV_8U);
  EXPECT_LE(cv::norm(mean, blurred, cv::NORM_INF), 1.0);
  EXPECT_GT(cv::norm(sharp, blurred, cv::NORM_INF), 50.0);  // the target moves fast at t = 0
}

// Interlaced: the even rows a quarter frame time before the frame's time, the odd rows
// a quarter after (fields half a frame time apart), each field blurred on its own.
TEST(PendulumScene, InterlacedFramesTakeTheirFieldsAtTwoInstants) {
  Settings s = noisyPendulum();
  s.virtual_scene.noise_sigma = 0.0;
  PendulumRenderWorkspace ws;
  cv::Mat frame, early, late;
  for (const MotionBlur& blur : {MotionBlur{}, MotionBlur{0.008, 4}}) {
    renderPendulumFrame(s, 0.0, blur, true, 0, frame, ws);
    renderPendulumFrame(s, -0.01, blur, false, 0, early, ws);
    renderPendulumFrame(s, 0.01, blur, false, 0, late, ws);
    ASSERT_EQ(frame.size(), early.size());
    for (int y = 0; y < frame.rows; ++y)
      ASSERT_EQ(cv::norm(frame.row(y), (y % 2 == 0 ? early : late).row(y), cv::NORM_INF), 0.0) << y;
    EXPECT_GT(cv::norm(early, late, cv::NORM_INF), 50.0);  // the fields differ: the comb of fig. 5.11
  }
  PendulumSource interlaced(s, MotionBlur{}, true);
  EXPECT_NE(interlaced.describe().find("interlaced"), std::string::npos);
}

// The still recording: the pendulum held at evenly spread angles, a few frames each.
TEST(PendulumScene, StillSourceHoldsThePendulumAtItsAngles) {
  const Settings s = noisyPendulum();
  PendulumStillSource still(s, PendulumStillParams{3, 20.0, 2});
  Frame f;
  std::vector<double> x;
  while (still.next(f) == Status::Ok) {
    ASSERT_TRUE(f.truth.has_value());
    x.push_back(f.truth->tx_mm);
    EXPECT_DOUBLE_EQ(f.timestamp_s, f.index / 25.0);
  }
  ASSERT_EQ(x.size(), 6u);
  EXPECT_DOUBLE_EQ(still.angleDeg(0), -20.0);
  EXPECT_DOUBLE_EQ(still.angleDeg(3), 0.0);
  EXPECT_DOUBLE_EQ(still.angleDeg(5), 20.0);
  EXPECT_DOUBLE_EQ(x[0], x[1]);  // held still
  EXPECT_NEAR(x[2], s.virtual_scene.pendulum.pivot_mm[0], 1e-9);
  EXPECT_NEAR(x[5] - x[2], s.virtual_scene.pendulum.length_mm * std::sin(20.0 * M_PI / 180.0), 1e-9);
  EXPECT_EQ(still.next(f), Status::EndOfStream);
}

}  // namespace
}  // namespace imagepro
