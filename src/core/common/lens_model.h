#pragma once
// The lens distortion model of thesis eq. 4.7 (docs/conventions.md), the one place it is
// written: in pixels relative to the principal point, distorted = q + delta(q) for the
// undistorted q. Its forward map, its Jacobian and its inverse by Newton's method serve
// the renderer (source/), the distortion correction (reconstruction/undistort.h) and the
// calibration alike.
#include <Eigen/Core>

namespace imagepro {

// Lens distortion coefficients of thesis eq. 4.7, in pixel units.
struct Distortion {
  double k1 = 0.0;  // px^-2
  double k2 = 0.0;  // px^-4
  double p1 = 0.0;  // px^-1
  double p2 = 0.0;  // px^-1

  bool isZero() const { return k1 == 0.0 && k2 == 0.0 && p1 == 0.0 && p2 == 0.0; }
};

// The distortion the thesis measured on its camera (thesis 4.6).
inline constexpr Distortion kThesisCameraDistortion{-2.05e-7, -1.21e-13, 3.39e-6, 2.56e-6};

// Distortion displacement delta(u_ud, v_ud) of eq. 4.7 (f_u, f_v of eqs. 4.15-4.16).
Eigen::Vector2d distortionDelta(const Distortion& d, const Eigen::Vector2d& undistortedRel);

// delta and its Jacobian [[d delta_u/du, d delta_u/dv], [d delta_v/du, d delta_v/dv]]
// (symmetric) at a point relative to the principal point.
struct DistortionJacobian {
  Eigen::Vector2d f;
  Eigen::Matrix2d J;
};
DistortionJacobian distortionWithJacobian(const Distortion& d, const Eigen::Vector2d& rel);

// The undistorted q with q + delta(q) = distortedRel, by Newton's method from the start
// that q holds. True once a step is shorter than `stepPx` (or the start is already within
// stepPx * 1e-6 of the solution). False, q holding the last iterate, after maxIterations
// steps or where an iterate lies beyond the fold of the model (the Jacobian of q + delta(q)
// not positive definite): with strong distortion image points there have no undistorted
// position.
bool invertDistortion(const Distortion& d, const Eigen::Vector2d& distortedRel, Eigen::Vector2d& q,
                      int maxIterations, double stepPx);

}  // namespace imagepro
