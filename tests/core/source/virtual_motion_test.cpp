#include "core/source/virtual_motion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/expect_pose.h"

namespace imagepro {
namespace {

VirtualSceneOptions motionScene(MotionKind kind, PoseAxis axis, double amplitude, double period) {
  VirtualSceneOptions s;
  s.initial_pose = Pose{5, -3, 2, 10, -20, 800};
  s.motion.kind = kind;
  s.motion.axis = axis;
  s.motion.amplitude = amplitude;
  s.motion.period_s = period;
  return s;
}

using test::expectPose;

TEST(VirtualMotion, StaticStaysAtTheInitialPose) {
  const auto s = motionScene(MotionKind::Static, PoseAxis::Tx, 100, 4);
  for (double t : {0.0, 1.3, 100.0}) expectPose(virtualPoseAt(s, t), s.initial_pose);
}

TEST(VirtualMotion, SinusoidAlongTx) {
  const auto s = motionScene(MotionKind::Sinusoid, PoseAxis::Tx, 100, 4);
  Pose want = s.initial_pose;
  expectPose(virtualPoseAt(s, 0.0), want);
  want.tx_mm = 110;
  expectPose(virtualPoseAt(s, 1.0), want);
  want.tx_mm = 10 - 100;
  expectPose(virtualPoseAt(s, 3.0), want);
  want.tx_mm = 10 + 100 * std::sin(M_PI / 4);
  expectPose(virtualPoseAt(s, 0.5), want);
  want.tx_mm = 10 + 100 * std::sin(2 * M_PI * 9.3 / 4);
  expectPose(virtualPoseAt(s, 9.3), want);
}

TEST(VirtualMotion, SinusoidAboutRz) {
  const auto s = motionScene(MotionKind::Sinusoid, PoseAxis::Rz, 30, 2);
  Pose want = s.initial_pose;
  want.rz_deg = 2 + 30;
  expectPose(virtualPoseAt(s, 0.5), want);
  want.rz_deg = 2 - 30;
  expectPose(virtualPoseAt(s, 1.5), want);
}

TEST(VirtualMotion, SawToothZigZagsAtConstantSpeed) {
  const auto s = motionScene(MotionKind::SawTooth, PoseAxis::Ty, 40, 4);
  auto ty = [&](double t) { return virtualPoseAt(s, t).ty_mm - s.initial_pose.ty_mm; };
  EXPECT_NEAR(ty(0.0), 0.0, 1e-9);
  EXPECT_NEAR(ty(0.5), 20.0, 1e-9);
  EXPECT_NEAR(ty(1.0), 40.0, 1e-9);
  EXPECT_NEAR(ty(2.0), 0.0, 1e-9);
  EXPECT_NEAR(ty(3.0), -40.0, 1e-9);
  EXPECT_NEAR(ty(4.0), 0.0, 1e-9);
  EXPECT_NEAR(ty(5.0), 40.0, 1e-9);
  // Constant speed 4A/T, rising in the first and last quarters, falling in between.
  for (double t = 0.05; t < 0.95; t += 0.17) EXPECT_NEAR(ty(t + 0.01) - ty(t), 4 * 40.0 / 4.0 * 0.01, 1e-9) << t;
  for (double t = 1.05; t < 2.95; t += 0.37) EXPECT_NEAR(ty(t + 0.01) - ty(t), -4 * 40.0 / 4.0 * 0.01, 1e-9) << t;
  // Other parameters untouched.
  EXPECT_NEAR(virtualPoseAt(s, 1.0).tx_mm, s.initial_pose.tx_mm, 1e-12);
  EXPECT_NEAR(virtualPoseAt(s, 1.0).rx_deg, s.initial_pose.rx_deg, 1e-12);
}

TEST(VirtualMotion, ConstantVelocityAdvancesByVelocityTimesDt) {
  VirtualSceneOptions s = motionScene(MotionKind::ConstantVelocity, PoseAxis::Tx, 0, 1);
  s.motion.velocity = Pose{2, -3, 5, 40, -25, 10};
  s.motion.wrap_box = Pose{0, 0, 0, 0, 0, 0};  // no wrapping: a straight run
  expectPose(virtualPoseAt(s, 0.0), s.initial_pose);
  const double dt = 0.04;  // one frame at 25 Hz
  for (double t : {0.0, 0.7, 3.1}) {
    const Pose a = virtualPoseAt(s, t), b = virtualPoseAt(s, t + dt);
    expectPose(Pose{b.rx_deg - a.rx_deg, b.ry_deg - a.ry_deg, b.rz_deg - a.rz_deg, b.tx_mm - a.tx_mm,
                    b.ty_mm - a.ty_mm, b.tz_mm - a.tz_mm},
               Pose{2 * dt, -3 * dt, 5 * dt, 40 * dt, -25 * dt, 10 * dt}, 1e-9);
  }
  expectPose(virtualPoseAt(s, 2.0), Pose{5 + 4, -3 - 6, 2 + 10, 10 + 80, -20 - 50, 800 + 20});
}

TEST(VirtualMotion, ConstantVelocityWrapsInsideTheBox) {
  VirtualSceneOptions s = motionScene(MotionKind::ConstantVelocity, PoseAxis::Tx, 0, 1);
  s.motion.velocity = Pose{0, 30, 0, 100, -60, 0};
  s.motion.wrap_box = Pose{0, 120, 360, 400, 300, 600};
  const Pose& p0 = s.initial_pose;
  // Tx leaves the box (+-200 mm about 10) after 2 s and comes back in on the other side.
  EXPECT_NEAR(virtualPoseAt(s, 1.9).tx_mm, p0.tx_mm + 190, 1e-9);
  EXPECT_NEAR(virtualPoseAt(s, 2.1).tx_mm, p0.tx_mm - 190, 1e-9);
  EXPECT_NEAR(virtualPoseAt(s, 5.0).tx_mm, p0.tx_mm + 100, 1e-9);  // 500 mm: once round, then 100
  // Ty runs the other way: it leaves at -150 and re-enters at +150.
  EXPECT_NEAR(virtualPoseAt(s, 2.4).ty_mm, p0.ty_mm - 144, 1e-9);
  EXPECT_NEAR(virtualPoseAt(s, 2.6).ty_mm, p0.ty_mm + 144, 1e-9);
  // Ry wraps at +-60 deg; Tz and Rx have no velocity and stay.
  EXPECT_NEAR(virtualPoseAt(s, 2.5).ry_deg, p0.ry_deg - 45, 1e-9);
  for (double t = 0.0; t < 30.0; t += 0.37) {
    const Pose p = virtualPoseAt(s, t);
    EXPECT_GE(p.tx_mm, p0.tx_mm - 200);
    EXPECT_LT(p.tx_mm, p0.tx_mm + 200);
    EXPECT_GE(p.ty_mm, p0.ty_mm - 150);
    EXPECT_LT(p.ty_mm, p0.ty_mm + 150);
    EXPECT_GE(p.ry_deg, p0.ry_deg - 60);
    EXPECT_LT(p.ry_deg, p0.ry_deg + 60);
    EXPECT_EQ(p.tz_mm, p0.tz_mm);
    EXPECT_EQ(p.rx_deg, p0.rx_deg);
  }
}

TEST(VirtualMotion, PendulumPeriodMatchesTheory) {
  PendulumOptions p;
  p.length_mm = 444;
  p.gravity_m_s2 = 9.80665;
  const double t0 = 2 * M_PI * std::sqrt(0.444 / 9.80665);  // eq. 5.1
  p.amplitude_deg = 1e-4;
  EXPECT_NEAR(pendulumPeriodS(p), t0, 1e-12);
  // Series of the large-amplitude period: T0 (1 + a^2/16 + 11 a^4/3072 + 173 a^6/737280 + ...).
  p.amplitude_deg = 15;
  const double a = 15 * M_PI / 180;
  const double series = t0 * (1 + a * a / 16 + 11 * std::pow(a, 4) / 3072 + 173 * std::pow(a, 6) / 737280);
  EXPECT_NEAR(pendulumPeriodS(p) / series, 1.0, 1e-8);
  // 60 degrees: T / T0 = 2 K(sin^2 30 deg) / pi, K(0.25) = 1.685750354812596.
  p.amplitude_deg = 60;
  EXPECT_NEAR(pendulumPeriodS(p) / t0, 2 * 1.685750354812596 / M_PI, 1e-12);
}

TEST(VirtualMotion, PendulumAngleSolvesTheEquationOfMotion) {
  PendulumOptions p;
  p.amplitude_deg = 50;
  const double period = pendulumPeriodS(p);
  EXPECT_NEAR(pendulumAngleDeg(p, 0), 0.0, 1e-9);
  EXPECT_NEAR(pendulumAngleDeg(p, period / 4), 50.0, 1e-7);
  EXPECT_NEAR(pendulumAngleDeg(p, period / 2), 0.0, 1e-7);
  EXPECT_NEAR(pendulumAngleDeg(p, 3 * period / 4), -50.0, 1e-7);
  EXPECT_NEAR(pendulumAngleDeg(p, 0.3 + 7 * period), pendulumAngleDeg(p, 0.3), 1e-7);
  // theta'' = -(g / L) sin(theta), by central differences.
  const double g_over_l = p.gravity_m_s2 * 1000 / p.length_mm;
  const double h = 1e-4;
  for (double t = 0.05; t < period; t += 0.071) {
    const double th = pendulumAngleDeg(p, t) * M_PI / 180;
    const double acc = (pendulumAngleDeg(p, t + h) - 2 * pendulumAngleDeg(p, t) + pendulumAngleDeg(p, t - h)) *
                       M_PI / 180 / (h * h);
    EXPECT_NEAR(acc, -g_over_l * std::sin(th), 1e-3 * g_over_l) << t;
  }
}

TEST(VirtualMotion, PendulumTargetMovesOnTheCircleAndTurnsWithTheRope) {
  VirtualSceneOptions s;
  s.motion.kind = MotionKind::Pendulum;
  s.initial_pose = Pose{0, 0, 0, 0, 0, 800};
  s.pendulum.pivot_mm = {20, -300, 1200};
  s.pendulum.length_mm = 444;
  s.pendulum.amplitude_deg = 20;
  const Eigen::Vector3d pivot(20, -300, 1200);
  // At rest (t = 0): straight below the pivot, facing the camera.
  expectPose(virtualPoseAt(s, 0), Pose{0, 0, 0, 20, 144, 1200});
  const double period = pendulumPeriodS(s.pendulum);
  for (double t = 0.02; t < period; t += period / 13) {
    const Pose pose = virtualPoseAt(s, t);
    const Eigen::Vector3d rope = translation(pose) - pivot;
    EXPECT_NEAR(rope.norm(), 444, 1e-9);
    EXPECT_NEAR(rope.z(), 0, 1e-9);  // swings along camera X
    const double theta = pendulumAngleDeg(s.pendulum, t);
    EXPECT_NEAR(rope.x(), 444 * std::sin(theta * M_PI / 180), 1e-9);
    // The target plane contains the rope: its normal stays perpendicular to it.
    EXPECT_NEAR((rotationMatrix(pose) * Eigen::Vector3d::UnitZ()).dot(rope), 0, 1e-9);
    EXPECT_NEAR(rotationAngleBetweenDeg(rotationMatrix(pose), Eigen::Matrix3d::Identity()), std::abs(theta), 1e-9);
  }
  // At the quarter period the rope is at the amplitude, to the right (+X).
  const Pose right = virtualPoseAt(s, period / 4);
  EXPECT_NEAR(right.tx_mm, 20 + 444 * std::sin(20 * M_PI / 180), 1e-6);
  EXPECT_NEAR(right.ty_mm, -300 + 444 * std::cos(20 * M_PI / 180), 1e-6);
  // Heading 90 degrees: the swing plane turns about Y (X towards -Z): it swings along Z.
  s.pendulum.swing_axis_deg = 90;
  const Pose towards = virtualPoseAt(s, period / 4);
  EXPECT_NEAR(towards.tx_mm, 20, 1e-6);
  EXPECT_NEAR(towards.tz_mm, 1200 - 444 * std::sin(20 * M_PI / 180), 1e-6);
}

TEST(VirtualMotion, KeysStepEachParameter) {
  VirtualSceneOptions s;
  s.key_step_mm = 5;
  s.key_step_deg = 1.5;
  Pose offset = kZeroPoseOffset;
  applyKey(VirtualKey::TxPlus, s, offset);
  applyKey(VirtualKey::TxPlus, s, offset);
  applyKey(VirtualKey::TyMinus, s, offset);
  applyKey(VirtualKey::TzPlus, s, offset);
  applyKey(VirtualKey::RxMinus, s, offset);
  applyKey(VirtualKey::RyPlus, s, offset);
  applyKey(VirtualKey::RzPlus, s, offset);
  applyKey(VirtualKey::RzPlus, s, offset);
  applyKey(VirtualKey::RzMinus, s, offset);
  expectPose(offset, Pose{-1.5, 1.5, 1.5, 10, -5, 5});
  applyKey(VirtualKey::TxMinus, s, offset);
  applyKey(VirtualKey::TyPlus, s, offset);
  applyKey(VirtualKey::TzMinus, s, offset);
  applyKey(VirtualKey::RxPlus, s, offset);
  applyKey(VirtualKey::RyMinus, s, offset);
  expectPose(offset, Pose{0, 0, 1.5, 5, 0, 0});
  expectPose(withOffset(Pose{1, 2, 3, 4, 5, 600}, offset), Pose{1, 2, 4.5, 9, 5, 600});
}

}  // namespace
}  // namespace imagepro
