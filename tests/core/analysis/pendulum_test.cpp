// The period estimate, the constrained sphere fit (thesis eqs. 5.2-5.6) and g on exact
// synthetic trajectories, and the named errors of degenerate data.
#include "core/analysis/pendulum.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/source/virtual_motion.h"

namespace imagepro {
namespace {

constexpr double kDeg = M_PI / 180.0;

VirtualSceneOptions pendulumScene(double length_mm, double amplitude_deg, double heading_deg = 0.0) {
  VirtualSceneOptions scene;
  scene.motion.kind = MotionKind::Pendulum;
  scene.pendulum.length_mm = length_mm;
  scene.pendulum.amplitude_deg = amplitude_deg;
  scene.pendulum.swing_axis_deg = heading_deg;
  // Turned about Y only: the rope stays in the target's plane, as eq. 5.3 requires.
  scene.initial_pose = Pose{0.0, -8.0, 0.0, 0.0, 0.0, 1000.0};
  return scene;
}

// Exact poses of the Virtual source's pendulum at `rate_hz` from t0.
std::vector<PoseSample> exactSwing(const VirtualSceneOptions& scene, double rate_hz, int frames, double t0 = 0.0) {
  std::vector<PoseSample> out;
  for (int i = 0; i < frames; ++i) {
    PoseSample s;
    s.t_s = t0 + i / rate_hz;
    s.valid = true;
    s.pose = virtualPoseAt(scene, s.t_s);
    out.push_back(s);
  }
  return out;
}

void split(const std::vector<PoseSample>& samples, std::vector<double>& t, std::vector<Eigen::Vector3d>& p,
           std::vector<Eigen::Vector3d>& n) {
  for (const PoseSample& s : samples) {
    if (!s.valid) continue;
    t.push_back(s.t_s);
    p.push_back(translation(s.pose));
    n.push_back(rotationMatrix(s.pose).col(2));
  }
}

// Points of an arc of `radius` about `centre` in the plane of normal `normal`.
void arc(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, double radius, double from_deg, double to_deg,
         int count, std::vector<Eigen::Vector3d>& p, std::vector<Eigen::Vector3d>& n) {
  const Eigen::Vector3d u = normal.normalized();
  const Eigen::Vector3d d = u.unitOrthogonal();
  const Eigen::Vector3d e = u.cross(d);
  for (int i = 0; i < count; ++i) {
    const double a = (from_deg + (to_deg - from_deg) * i / (count - 1)) * kDeg;
    p.push_back(centre + radius * (std::cos(a) * d + std::sin(a) * e));
    n.push_back(u);
  }
}

TEST(PeriodFactor, MatchesTheVirtualPendulumsExactPeriod) {
  for (double amplitude : {1.0, 15.0, 40.0, 90.0}) {
    PendulumOptions p;
    p.amplitude_deg = amplitude;
    const double small = 2.0 * M_PI * std::sqrt(p.length_mm / 1000.0 / p.gravity_m_s2);
    EXPECT_NEAR(pendulumPeriodFactor(amplitude * kDeg), pendulumPeriodS(p) / small, 1e-12) << amplitude;
  }
  EXPECT_NEAR(pendulumPeriodFactor(0.0), 1.0, 1e-15);
  // The series 1 + theta^2 / 16 for a small swing.
  EXPECT_NEAR(pendulumPeriodFactor(0.1), 1.0 + 0.01 / 16.0, 1e-6);
}

TEST(SphereFit, ExactArcGivesPivotAndLength) {
  const Eigen::Vector3d pivot(40.0, -320.0, 1150.0);
  for (const Eigen::Vector3d& normal : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.3, -0.2, 1.0),
                                        Eigen::Vector3d(1.0, 0.1, 0.4)}) {
    std::vector<Eigen::Vector3d> p, n;
    arc(pivot, normal, 444.0, 70.0, 110.0, 60, p, n);
    SphereFit fit;
    ASSERT_EQ(fitConstrainedSphere(p, n, fit), Status::Ok);
    EXPECT_NEAR(fit.radius_mm, 444.0, 1e-7);
    EXPECT_LT((fit.centre_mm - pivot).norm(), 1e-7);
    EXPECT_LT(fit.radial_rms_mm, 1e-7);
    EXPECT_LT(fit.normal_rms_mm, 1e-7);
    EXPECT_LT(fit.radius_sigma_mm, 1e-4);
    EXPECT_EQ(fit.points, 60);
  }
}

TEST(SphereFit, FivePositionedFramesAsInTheThesis) {
  // Thesis fig. 5.12: the pendulum stopped at five positions.
  std::vector<Eigen::Vector3d> p, n;
  arc(Eigen::Vector3d(0, -300, 1200), Eigen::Vector3d(0, 0, 1), 444.0, -20.0, 20.0, 5, p, n);
  SphereFit fit;
  ASSERT_EQ(fitConstrainedSphere(p, n, fit), Status::Ok);
  EXPECT_NEAR(fit.radius_mm, 444.0, 1e-7);
}

TEST(SphereFit, UncertaintyMatchesTheScatterOfNoisyFits) {
  // Noise like the reconstruction's (0.05 mm across the view, 0.4 mm in depth, 0.2 deg
  // on the normal) on a 30 degree arc: the reported sigma is the spread of the results.
  const Eigen::Vector3d pivot(0, -300, 1200), axis(0, 0, 1);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> errors;
  double sigma_sum = 0.0;
  const int trials = 200;
  for (int k = 0; k < trials; ++k) {
    std::vector<Eigen::Vector3d> p, n;
    arc(pivot, axis, 444.0, 75.0, 105.0, 150, p, n);
    for (std::size_t i = 0; i < p.size(); ++i) {
      p[i] += Eigen::Vector3d(0.05 * gauss(rng), 0.05 * gauss(rng), 0.4 * gauss(rng));
      n[i] = (n[i] + Eigen::Vector3d(0.0035 * gauss(rng), 0.0035 * gauss(rng), 0.0)).normalized();
    }
    SphereFit fit;
    ASSERT_EQ(fitConstrainedSphere(p, n, fit), Status::Ok);
    errors.push_back(fit.radius_mm - 444.0);
    sigma_sum += fit.radius_sigma_mm;
  }
  double mean = 0.0, var = 0.0;
  for (double e : errors) mean += e / trials;
  for (double e : errors) var += (e - mean) * (e - mean) / trials;
  const double spread = std::sqrt(var), reported = sigma_sum / trials;
  EXPECT_GT(reported, 0.7 * spread);
  EXPECT_LT(reported, 1.4 * spread);
  EXPECT_LT(std::abs(mean), 3.0 * spread / std::sqrt(trials) + 0.02);  // no bias to speak of
  EXPECT_LT(spread, 0.5);
}

TEST(SphereFit, DegenerateInputsGiveNamedErrors) {
  std::vector<Eigen::Vector3d> p, n;
  SphereFit fit;
  EXPECT_EQ(fitConstrainedSphere(p, n, fit), Status::TooFewFrames);
  arc(Eigen::Vector3d(0, 0, 1000), Eigen::Vector3d(0, 0, 1), 400.0, 80.0, 100.0, 3, p, n);
  EXPECT_EQ(fitConstrainedSphere(p, n, fit), Status::TooFewFrames);
  // Positions on a line leave the centre free along it.
  p.clear();
  n.clear();
  for (int i = 0; i < 20; ++i) {
    p.emplace_back(10.0 * i, 0.0, 1000.0);
    n.emplace_back(0.0, 0.0, 1.0);
  }
  EXPECT_EQ(fitConstrainedSphere(p, n, fit), Status::DegenerateFit);
  n.pop_back();
  EXPECT_EQ(fitConstrainedSphere(p, n, fit), Status::DegenerateFit);
}

TEST(Period, ExactLargeAmplitudeSwing) {
  for (double amplitude : {5.0, 15.0, 30.0}) {
    for (double heading : {0.0, 30.0}) {
      const VirtualSceneOptions scene = pendulumScene(444.0, amplitude, heading);
      std::vector<double> t;
      std::vector<Eigen::Vector3d> p, n;
      split(exactSwing(scene, 25.0, 250, 0.37), t, p, n);
      PeriodEstimate est;
      ASSERT_EQ(estimatePeriod(t, p, est), Status::Ok) << amplitude;
      const double truth = pendulumPeriodS(scene.pendulum);
      EXPECT_NEAR(est.period_s, truth, 2e-5 * truth) << amplitude << " " << heading;
      EXPECT_LT(est.period_sigma_s, 1e-4);
      EXPECT_GE(est.crossings, 13);
      EXPECT_GT(est.sine_fraction, 0.99);
      // The swing direction: camera X turned by the heading about Y.
      const Eigen::Vector3d dir(std::cos(heading * kDeg), 0.0, -std::sin(heading * kDeg));
      EXPECT_GT(std::abs(est.direction.dot(dir)), 0.999);
    }
  }
}

TEST(Period, SinusoidWithMissingFramesAndAnOffsetLevel) {
  // Every third frame lost in bursts and an asymmetric record: the level the sinusoid
  // gives and the two intercepts make the period exact.
  std::vector<double> t;
  std::vector<Eigen::Vector3d> p;
  const double period = 1.3371;
  for (int i = 0; i < 300; ++i) {
    if (i % 7 == 3 || i % 7 == 4) continue;
    const double ti = 0.11 + i / 25.0;
    t.push_back(ti);
    p.emplace_back(80.0 * std::sin(2 * M_PI * ti / period + 0.4) + 3.0, 100.0, 900.0);
  }
  PeriodEstimate est;
  ASSERT_EQ(estimatePeriod(t, p, est), Status::Ok);
  EXPECT_NEAR(est.period_s, period, 2e-6);
  EXPECT_NEAR(est.amplitude_mm, 80.0, 1e-6);
}

TEST(Period, DegenerateRecordsGiveNamedErrors) {
  PeriodEstimate est;
  std::vector<double> t;
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 5; ++i) {
    t.push_back(i * 0.04);
    p.emplace_back(std::sin(i), 0, 1000);
  }
  EXPECT_EQ(estimatePeriod(t, p, est), Status::TooFewFrames);

  // Standing still.
  t.clear();
  p.clear();
  for (int i = 0; i < 100; ++i) {
    t.push_back(i * 0.04);
    p.emplace_back(12.0, 40.0, 1000.0);
  }
  EXPECT_EQ(estimatePeriod(t, p, est), Status::NoSwing);

  // Noise only (a target held still, reconstructed with noise).
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss(0.0, 0.3);
  for (auto& q : p) q += Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  EXPECT_EQ(estimatePeriod(t, p, est), Status::NoSwing);

  // A steady drift is no swing either.
  for (int i = 0; i < 100; ++i) p[i] = Eigen::Vector3d(2.0 * i, 0, 1000);
  EXPECT_EQ(estimatePeriod(t, p, est), Status::NoSwing);

  // A swing, but only one period of it: fewer than four crossings.
  for (int i = 0; i < 100; ++i) p[i] = Eigen::Vector3d(50.0 * std::sin(2 * M_PI * t[i] / 3.5), 0, 1000);
  EXPECT_EQ(estimatePeriod(t, p, est), Status::NoSwing);

  // Times that do not increase.
  for (int i = 0; i < 100; ++i) p[i] = Eigen::Vector3d(50.0 * std::sin(2 * M_PI * t[i] / 1.3), 0, 1000);
  t[50] = t[49];
  EXPECT_EQ(estimatePeriod(t, p, est), Status::DegenerateFit);
  p.pop_back();
  EXPECT_EQ(estimatePeriod(t, p, est), Status::DegenerateFit);
}

TEST(Pendulum, GravityFromAnExactTrajectory) {
  const VirtualSceneOptions scene = pendulumScene(444.0, 15.0);
  PendulumAnalysis a;
  ASSERT_EQ(analyzePendulum(exactSwing(scene, 25.0, 300), {}, a), Status::Ok);
  EXPECT_NEAR(a.length_mm, 444.0, 1e-6);
  EXPECT_NEAR(a.period_s, pendulumPeriodS(scene.pendulum), 2e-5);
  EXPECT_NEAR(a.amplitude_deg, 15.0, 0.05);
  EXPECT_NEAR(a.small_amplitude_period_s, 2 * M_PI * std::sqrt(0.444 / scene.pendulum.gravity_m_s2), 3e-5);
  EXPECT_NEAR(a.g_m_s2, scene.pendulum.gravity_m_s2, 5e-4);
  EXPECT_LT(a.g_sigma_m_s2, 5e-4);
  EXPECT_EQ(a.frames, 300);
  EXPECT_EQ(a.valid_frames, 300);
  ASSERT_EQ(a.swing_angle_deg.size(), 300u);
  EXPECT_NEAR(a.swing_angle_deg[0], 0.0, 0.1);  // t = 0 is the lowest point
  // Eq. 5.1 with the measured period underestimates g by about theta0^2 / 8.
  const double under = 1.0 - a.g_uncorrected_m_s2 / scene.pendulum.gravity_m_s2;
  EXPECT_NEAR(under, std::pow(15.0 * kDeg, 2) / 8.0, 0.001);

  PendulumAnalysisOptions plain;
  plain.amplitude_correction = false;
  ASSERT_EQ(analyzePendulum(exactSwing(scene, 25.0, 300), plain, a), Status::Ok);
  EXPECT_DOUBLE_EQ(a.g_m_s2, a.g_uncorrected_m_s2);
}

// One timestamp far off (a corrupt data-out row) made the period's frequency scan ask for
// one step per 1/(4 x duration) up to the Nyquist frequency: over 10^8 steps, and
// gigabytes, for a 300-frame record. The scan's steps are now bounded by the samples, and
// the rest of the record still gives g.
TEST(Pendulum, ATimestampFarOffCostsNoMoreThanTheRecord) {
  const VirtualSceneOptions scene = pendulumScene(444.0, 15.0);
  std::vector<PoseSample> swing = exactSwing(scene, 25.0, 300);
  swing.back().t_s = 1e7;
  PendulumAnalysis a;
  ASSERT_EQ(analyzePendulum(swing, {}, a), Status::Ok);
  EXPECT_EQ(a.frames, 300);
  EXPECT_NEAR(a.g_m_s2, scene.pendulum.gravity_m_s2, 1e-3);
}

TEST(Pendulum, DegenerateSequencesGiveNamedErrors) {
  const VirtualSceneOptions scene = pendulumScene(444.0, 15.0);
  PendulumAnalysis a;
  EXPECT_EQ(analyzePendulum({}, {}, a), Status::TooFewFrames);
  EXPECT_EQ(analyzePendulum(exactSwing(scene, 25.0, 6), {}, a), Status::TooFewFrames);

  // Lost in half of the frames.
  std::vector<PoseSample> lost = exactSwing(scene, 25.0, 200);
  for (std::size_t i = 0; i < lost.size(); i += 2) lost[i].valid = false;
  EXPECT_EQ(analyzePendulum(lost, {}, a), Status::TargetLost);
  EXPECT_EQ(a.valid_frames, 100);
  // ... but a third lost is fine.
  lost = exactSwing(scene, 25.0, 200);
  for (std::size_t i = 0; i < lost.size(); i += 3) lost[i].valid = false;
  EXPECT_EQ(analyzePendulum(lost, {}, a), Status::Ok);
  EXPECT_NEAR(a.length_mm, 444.0, 1e-6);

  // Hanging still.
  VirtualSceneOptions still = scene;
  still.pendulum.amplitude_deg = 0.0;
  EXPECT_EQ(analyzePendulum(exactSwing(still, 25.0, 200), {}, a), Status::NoSwing);
}

// The thesis's period: first to last maximum per axis, averaged over the axes that move
// at the swing's period.
TEST(MaximaPeriod, AxesAtTheSwingsPeriodOnly) {
  // Swinging along camera X: Tx at the period, Ty (the height) at twice it, Tz still.
  VirtualSceneOptions scene = pendulumScene(444.0, 15.0);
  std::vector<double> t;
  std::vector<Eigen::Vector3d> p, n;
  split(exactSwing(scene, 25.0, 300), t, p, n);
  const double truth = pendulumPeriodS(scene.pendulum);
  MaximaPeriod m;
  ASSERT_EQ(estimatePeriodByMaxima(t, p, truth, m), Status::Ok);
  EXPECT_EQ(m.axes, 1);
  EXPECT_GE(m.axis_cycles[0], 8);
  EXPECT_EQ(m.axis_cycles[1], 0);
  EXPECT_EQ(m.axis_cycles[2], 0);
  // Each maximum is a frame: within a frame time over the cycles.
  EXPECT_NEAR(m.period_s, truth, 0.04 / m.axis_cycles[0]);
  EXPECT_GE(m.period_sigma_s, 0.04 / (std::sqrt(6.0) * m.axis_cycles[0]) - 1e-12);

  // Turned 40 degrees towards the camera: Tz swings at the period too.
  scene = pendulumScene(444.0, 15.0, 40.0);
  t.clear(), p.clear(), n.clear();
  split(exactSwing(scene, 25.0, 300), t, p, n);
  ASSERT_EQ(estimatePeriodByMaxima(t, p, truth, m), Status::Ok);
  EXPECT_EQ(m.axes, 2);
  EXPECT_GE(m.axis_cycles[2], 7);
  EXPECT_NEAR(m.period_s, truth, 0.04 / m.axis_cycles[0]);

  // A top at the record's last frame is no maximum (the record may stop on the way up).
  std::vector<double> t2;
  std::vector<Eigen::Vector3d> p2;
  for (int i = 0; i <= 125; ++i) {
    t2.push_back(0.01 * i);
    p2.emplace_back(std::sin(2 * M_PI * (0.01 * i) / 0.5 - M_PI / 2), 0.0, 0.0);  // 0.5 s, minima at 0, 0.5 ...
  }
  ASSERT_EQ(estimatePeriodByMaxima(t2, p2, 0.5, m), Status::Ok);
  EXPECT_EQ(m.axis_cycles[0], 1);  // maxima at 0.25 and 0.75, not the last frame's 1.25
  EXPECT_NEAR(m.period_s, 0.5, 1e-9);
}

TEST(MaximaPeriod, NamedErrors) {
  std::vector<double> t(50);
  std::vector<Eigen::Vector3d> p(50, Eigen::Vector3d(0, 0, 1000));
  for (int i = 0; i < 50; ++i) t[i] = 0.04 * i;
  MaximaPeriod m;
  EXPECT_EQ(estimatePeriodByMaxima(t, p, 1.3, m), Status::NoSwing);  // nothing moves
  EXPECT_EQ(estimatePeriodByMaxima(t, p, 0.0, m), Status::DegenerateFit);
  EXPECT_EQ(estimatePeriodByMaxima(std::span(t).first(5), std::span(p).first(5), 1.3, m), Status::TooFewFrames);
  p.pop_back();
  EXPECT_EQ(estimatePeriodByMaxima(t, p, 1.3, m), Status::DegenerateFit);
}

TEST(Pendulum, PeriodMethodChoosesThePeriodOfG) {
  const VirtualSceneOptions scene = pendulumScene(444.0, 15.0);
  PendulumAnalysisOptions options;
  options.period_method = PeriodMethod::Maxima;
  PendulumAnalysis a;
  ASSERT_EQ(analyzePendulum(exactSwing(scene, 25.0, 300), options, a), Status::Ok);
  ASSERT_EQ(a.maxima_status, Status::Ok);
  EXPECT_DOUBLE_EQ(a.period_s, a.maxima.period_s);
  EXPECT_DOUBLE_EQ(a.period_sigma_s, a.maxima.period_sigma_s);
  // Both estimates are kept; the crossings' is the sharper.
  const double truth = pendulumPeriodS(scene.pendulum);
  EXPECT_NEAR(a.period.period_s, truth, 2e-5);
  EXPECT_NEAR(a.maxima.period_s, truth, 0.004);
  EXPECT_NEAR(a.g_m_s2, scene.pendulum.gravity_m_s2 * std::pow(a.period.period_s / a.maxima.period_s, 2), 1e-3);
}

// The thesis's way: the length from frames of the pendulum held still at five places,
// the period from a small swing that alone fixes no sphere.
TEST(Pendulum, LengthFromStillFramesPeriodFromASwing) {
  VirtualSceneOptions scene = pendulumScene(444.0, 3.0, 20.0);
  std::vector<PoseSample> still;
  for (double angle : {-20.0, -10.0, 0.0, 10.0, 20.0}) {
    PoseSample s;
    s.t_s = static_cast<double>(still.size());
    s.valid = true;
    s.pose = pendulumPoseAtAngle(scene, angle);
    still.push_back(s);
  }
  const std::vector<PoseSample> swing = exactSwing(scene, 25.0, 300);
  PendulumAnalysis a;
  ASSERT_EQ(analyzePendulumStillSwing(still, swing, {}, a), Status::Ok);
  EXPECT_TRUE(a.length_from_still);
  EXPECT_EQ(a.still_frames, 5);
  EXPECT_EQ(a.still_valid_frames, 5);
  EXPECT_EQ(a.sphere.points, 5);
  EXPECT_NEAR(a.length_mm, 444.0, 1e-6);
  EXPECT_NEAR(a.period_s, pendulumPeriodS(scene.pendulum), 2e-5);
  EXPECT_NEAR(a.amplitude_deg, 3.0, 0.05);  // the swing's, about the still frames' pivot
  EXPECT_NEAR(a.g_m_s2, scene.pendulum.gravity_m_s2, 5e-4);
}

TEST(Pendulum, StillRecordingErrorsAreNamedAsItsOwn) {
  const VirtualSceneOptions scene = pendulumScene(444.0, 15.0);
  const std::vector<PoseSample> swing = exactSwing(scene, 25.0, 200);
  std::vector<PoseSample> still;
  for (double angle : {-20.0, 0.0, 20.0}) {
    PoseSample s;
    s.valid = true;
    s.pose = pendulumPoseAtAngle(scene, angle);
    still.push_back(s);
  }
  PendulumAnalysis a;
  EXPECT_EQ(analyzePendulumStillSwing(still, swing, {}, a), Status::TooFewFrames);  // three places
  EXPECT_TRUE(a.still_failed);
  EXPECT_EQ(a.still_valid_frames, 3);
  // Five frames, all in one place: no sphere.
  still.assign(5, still[1]);
  EXPECT_EQ(analyzePendulumStillSwing(still, swing, {}, a), Status::DegenerateFit);
  EXPECT_TRUE(a.still_failed);
  // A swing that fails is the swing's failure.
  EXPECT_EQ(analyzePendulumStillSwing(still, std::span(swing).first(5), {}, a), Status::TooFewFrames);
  EXPECT_FALSE(a.still_failed);
}

}  // namespace
}  // namespace imagepro
