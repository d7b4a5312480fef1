#include "core/reconstruction/undistort.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace imagepro {

DistortionJacobian distortionWithJacobian(const Distortion& d, const Eigen::Vector2d& rel) {
  const double u = rel.x();
  const double v = rel.y();
  const double uu = u * u;
  const double vv = v * v;
  const double uv = u * v;
  const double r2 = uu + vv;
  const double radial = d.k1 * r2 + d.k2 * r2 * r2;
  // d(radial)/du = 2u (k1 + 2 k2 r^2), likewise for v.
  const double dRadialCoef = 2.0 * (d.k1 + 2.0 * d.k2 * r2);
  DistortionJacobian out;
  out.f.x() = u * radial + 2.0 * d.p1 * uv + d.p2 * (r2 + 2.0 * uu);
  out.f.y() = v * radial + d.p1 * (r2 + 2.0 * vv) + 2.0 * d.p2 * uv;
  const double cross = uv * dRadialCoef + 2.0 * d.p1 * u + 2.0 * d.p2 * v;  // df_u/dv = df_v/du
  out.J(0, 0) = radial + uu * dRadialCoef + 2.0 * d.p1 * v + 6.0 * d.p2 * u;
  out.J(0, 1) = cross;
  out.J(1, 0) = cross;
  out.J(1, 1) = radial + vv * dRadialCoef + 6.0 * d.p1 * v + 2.0 * d.p2 * u;
  return out;
}

Eigen::Vector2d undistortTaylor(const CameraModel& cam, const Eigen::Vector2d& distortedPx) {
  const Eigen::Vector2d c(cam.u0(), cam.v0());
  // Eqs. 4.18-4.19: f and its derivatives evaluated at the distorted point itself.
  const DistortionJacobian fj = distortionWithJacobian(cam.distortion, distortedPx - c);
  const double fu = fj.f.x(), fv = fj.f.y();
  const double fu_u = fj.J(0, 0), fu_v = fj.J(0, 1), fv_u = fj.J(1, 0), fv_v = fj.J(1, 1);
  const double denominator = 1.0 + fu_u + fv_v;
  return {distortedPx.x() + (-fu + fv * fu_v - fu * fv_v) / denominator,
          distortedPx.y() + (-fv + fu * fv_u - fv * fu_u) / denominator};
}

Eigen::Vector2d undistortExact(const CameraModel& cam, const Eigen::Vector2d& distortedPx,
                               int maxIterations) {
  const Eigen::Vector2d c(cam.u0(), cam.v0());
  const Eigen::Vector2d x = distortedPx - c;
  Eigen::Vector2d y = undistortTaylor(cam, distortedPx) - c;
  for (int i = 0; i < maxIterations; ++i) {
    const DistortionJacobian fj = distortionWithJacobian(cam.distortion, y);
    const Eigen::Vector2d residual = y + fj.f - x;
    const Eigen::Matrix2d A = Eigen::Matrix2d::Identity() + fj.J;
    const double det = A.determinant();
    if (!(std::abs(det) > 1e-12)) break;  // the model folds here: keep the last iterate
    const Eigen::Vector2d step = A.inverse() * residual;
    y -= step;
    if (step.squaredNorm() < 1e-24) break;
  }
  return y + c;
}

void undistortPoints(const CameraModel& cam, bool exact, std::span<Eigen::Vector2d> points) {
  if (cam.distortion.isZero()) return;
  if (exact) {
    for (Eigen::Vector2d& p : points) p = undistortExact(cam, p);
  } else {
    for (Eigen::Vector2d& p : points) p = undistortTaylor(cam, p);
  }
}

UndistortionError measureTaylorUndistortionError(const CameraModel& cam) {
  UndistortionError e;
  double sum2 = 0.0;
  for (int v = 0; v < cam.height; ++v) {
    for (int u = 0; u < cam.width; ++u) {
      const Eigen::Vector2d x(u, v);
      const Eigen::Vector2d truth = undistortExact(cam, x);
      e.max_residual_exact_px =
          std::max(e.max_residual_exact_px, (distortPixel(cam, truth) - x).norm());
      const double err = (undistortTaylor(cam, x) - truth).norm();
      e.max_px = std::max(e.max_px, err);
      sum2 += err * err;
    }
  }
  const double n = static_cast<double>(cam.width) * cam.height;
  e.rms_px = n > 0 ? std::sqrt(sum2 / n) : 0.0;
  return e;
}

}  // namespace imagepro
