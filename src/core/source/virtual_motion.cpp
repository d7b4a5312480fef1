#include "core/source/virtual_motion.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace imagepro {
namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

double& axisValue(Pose& p, PoseAxis axis) {
  switch (axis) {
    case PoseAxis::Tx: return p.tx_mm;
    case PoseAxis::Ty: return p.ty_mm;
    case PoseAxis::Tz: return p.tz_mm;
    case PoseAxis::Rx: return p.rx_deg;
    case PoseAxis::Ry: return p.ry_deg;
    case PoseAxis::Rz: return p.rz_deg;
  }
  return p.tx_mm;
}

// Jacobi amplitude by the arithmetic-geometric mean (Abramowitz & Stegun 16.4):
// returns sn(u | m) and sets `quarter_period` to K(m). Valid for 0 <= m < 1.
double jacobiSn(double u, double m, double& quarter_period) {
  constexpr int kMaxSteps = 32;
  double a[kMaxSteps + 1];
  double c[kMaxSteps + 1];
  a[0] = 1.0;
  c[0] = std::sqrt(m);
  double b = std::sqrt(1.0 - m);
  int n = 0;
  while (n < kMaxSteps && std::abs(c[n]) > 1e-16) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    ++n;
  }
  quarter_period = M_PI / (2.0 * a[n]);
  double phi = std::ldexp(a[n] * u, n);
  for (int k = n; k > 0; --k) phi = 0.5 * (phi + std::asin(c[k] / a[k] * std::sin(phi)));
  return std::sin(phi);
}

double omega0(const PendulumOptions& p) {
  return std::sqrt(p.gravity_m_s2 * 1000.0 / p.length_mm);  // rad/s, lengths in mm
}

// `offset` brought into [-width/2, width/2) by whole widths; a width of 0 leaves it as it is.
double wrapped(double offset, double width) {
  if (!(width > 0.0)) return offset;
  return offset - width * std::floor(offset / width + 0.5);
}

}  // namespace

double pendulumPeriodS(const PendulumOptions& pendulum) {
  const double k = std::sin(0.5 * std::abs(pendulum.amplitude_deg) * kRadPerDeg);
  double quarter = 0.0;
  jacobiSn(0.0, k * k, quarter);
  return 4.0 * quarter / omega0(pendulum);
}

double pendulumAngleDeg(const PendulumOptions& pendulum, double t_s) {
  const double amplitude = std::abs(pendulum.amplitude_deg) * kRadPerDeg;
  const double k = std::sin(0.5 * amplitude);
  double quarter = 0.0;
  const double sn = jacobiSn(omega0(pendulum) * t_s, k * k, quarter);
  const double theta = 2.0 * std::asin(std::clamp(k * sn, -1.0, 1.0));
  return std::copysign(1.0, pendulum.amplitude_deg) * theta / kRadPerDeg;
}

Pose pendulumPoseAtAngle(const VirtualSceneOptions& scene, double theta_deg) {
  const PendulumOptions& p = scene.pendulum;
  const double heading = p.swing_axis_deg * kRadPerDeg;
  // Swing direction: camera X turned by the heading about Y; the rope turns about
  // the horizontal axis perpendicular to it, taking "down" (+Y) towards it.
  const Eigen::Vector3d swing_dir(std::cos(heading), 0.0, -std::sin(heading));
  const Eigen::Vector3d turn_axis = Eigen::Vector3d::UnitY().cross(swing_dir);
  const Eigen::Matrix3d swing = Eigen::AngleAxisd(theta_deg * kRadPerDeg, turn_axis).toRotationMatrix();
  const Eigen::Vector3d pivot(p.pivot_mm[0], p.pivot_mm[1], p.pivot_mm[2]);
  const Eigen::Vector3d centre = pivot + swing * Eigen::Vector3d(0.0, p.length_mm, 0.0);
  return poseFromRt(swing * rotationMatrix(scene.initial_pose), centre);
}

Pose virtualPoseAt(const VirtualSceneOptions& scene, double t_s) {
  Pose pose = scene.initial_pose;
  const MotionOptions& m = scene.motion;
  const double phase = m.period_s > 0.0 ? t_s / m.period_s : 0.0;
  switch (m.kind) {
    case MotionKind::Static:
      break;
    case MotionKind::Sinusoid:
      axisValue(pose, m.axis) += m.amplitude * std::sin(2.0 * M_PI * phase);
      break;
    case MotionKind::SawTooth: {
      // Triangle wave: |.| of a saw-tooth shifted so it starts at 0 going up.
      const double x = phase + 0.25;
      axisValue(pose, m.axis) += m.amplitude * (1.0 - 4.0 * std::abs(x - std::floor(x) - 0.5));
      break;
    }
    case MotionKind::Pendulum:
      pose = pendulumPoseAtAngle(scene, pendulumAngleDeg(scene.pendulum, t_s));
      break;
    case MotionKind::ConstantVelocity: {
      const Pose& v = m.velocity;
      const Pose& box = m.wrap_box;
      pose.rx_deg += wrapped(v.rx_deg * t_s, box.rx_deg);
      pose.ry_deg += wrapped(v.ry_deg * t_s, box.ry_deg);
      pose.rz_deg += wrapped(v.rz_deg * t_s, box.rz_deg);
      pose.tx_mm += wrapped(v.tx_mm * t_s, box.tx_mm);
      pose.ty_mm += wrapped(v.ty_mm * t_s, box.ty_mm);
      pose.tz_mm += wrapped(v.tz_mm * t_s, box.tz_mm);
      break;
    }
  }
  return pose;
}

void applyKey(VirtualKey key, const VirtualSceneOptions& scene, Pose& offset) {
  const double mm = scene.key_step_mm;
  const double deg = scene.key_step_deg;
  switch (key) {
    case VirtualKey::TxMinus: offset.tx_mm -= mm; break;
    case VirtualKey::TxPlus: offset.tx_mm += mm; break;
    case VirtualKey::TyMinus: offset.ty_mm -= mm; break;
    case VirtualKey::TyPlus: offset.ty_mm += mm; break;
    case VirtualKey::TzMinus: offset.tz_mm -= mm; break;
    case VirtualKey::TzPlus: offset.tz_mm += mm; break;
    case VirtualKey::RxMinus: offset.rx_deg -= deg; break;
    case VirtualKey::RxPlus: offset.rx_deg += deg; break;
    case VirtualKey::RyMinus: offset.ry_deg -= deg; break;
    case VirtualKey::RyPlus: offset.ry_deg += deg; break;
    case VirtualKey::RzMinus: offset.rz_deg -= deg; break;
    case VirtualKey::RzPlus: offset.rz_deg += deg; break;
  }
}

Pose withOffset(const Pose& pose, const Pose& offset) {
  return Pose{pose.rx_deg + offset.rx_deg, pose.ry_deg + offset.ry_deg, pose.rz_deg + offset.rz_deg,
              pose.tx_mm + offset.tx_mm,   pose.ty_mm + offset.ty_mm,   pose.tz_mm + offset.tz_mm};
}

}  // namespace imagepro
