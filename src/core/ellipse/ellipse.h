#pragma once
// An ellipse in image coordinates, both as its geometric parameters and as the
// conic a*u^2 + b*u*v + c*v^2 + d*u + e*v + f = 0 (thesis eq. 2.29), the form the
// reconstruction consumes.
#include <Eigen/Core>

namespace imagepro {

struct Ellipse {
  double cx = 0.0, cy = 0.0;  // centre, pixels
  double a = 0.0, b = 0.0;    // semi-axes, a >= b, pixels
  double angle_deg = 0.0;     // of the major axis from +u towards +v, in (-90, 90]
};

using Conic = Eigen::Matrix<double, 6, 1>;  // (a, b, c, d, e, f), normalised to unit norm

Conic conicFromEllipse(const Ellipse& e);
// False when the conic is not a real ellipse.
bool ellipseFromConic(const Conic& c, Ellipse& out);
// 3x3 symmetric matrix form: x^T M x = 0 with x = (u, v, 1).
Eigen::Matrix3d conicMatrix(const Conic& c);

}  // namespace imagepro
