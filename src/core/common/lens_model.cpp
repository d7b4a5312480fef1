#include "core/common/lens_model.h"

namespace imagepro {

namespace {

// The powers of a point that delta and its Jacobian share.
struct Terms {
  double u, v, uu, vv, uv, r2, radial;

  Terms(const Distortion& d, const Eigen::Vector2d& rel)
      : u(rel.x()), v(rel.y()), uu(u * u), vv(v * v), uv(u * v), r2(uu + vv), radial(d.k1 * r2 + d.k2 * r2 * r2) {}

  Eigen::Vector2d delta(const Distortion& d) const {
    return {u * radial + 2.0 * d.p1 * uv + d.p2 * (r2 + 2.0 * uu),
            v * radial + d.p1 * (r2 + 2.0 * vv) + 2.0 * d.p2 * uv};
  }
};

}  // namespace

Eigen::Vector2d distortionDelta(const Distortion& d, const Eigen::Vector2d& undistortedRel) {
  return Terms(d, undistortedRel).delta(d);
}

DistortionJacobian distortionWithJacobian(const Distortion& d, const Eigen::Vector2d& rel) {
  const Terms t(d, rel);
  const double u = t.u, v = t.v, uu = t.uu, vv = t.vv, uv = t.uv, radial = t.radial;
  // d(radial)/du = 2u (k1 + 2 k2 r^2), likewise for v.
  const double dRadialCoef = 2.0 * (d.k1 + 2.0 * d.k2 * t.r2);
  DistortionJacobian out;
  out.f = t.delta(d);
  const double cross = uv * dRadialCoef + 2.0 * d.p1 * u + 2.0 * d.p2 * v;  // df_u/dv = df_v/du
  out.J(0, 0) = radial + uu * dRadialCoef + 2.0 * d.p1 * v + 6.0 * d.p2 * u;
  out.J(0, 1) = cross;
  out.J(1, 0) = cross;
  out.J(1, 1) = radial + vv * dRadialCoef + 6.0 * d.p1 * v + 2.0 * d.p2 * u;
  return out;
}

bool invertDistortion(const Distortion& d, const Eigen::Vector2d& distortedRel, Eigen::Vector2d& q,
                      int maxIterations, double stepPx) {
  const double startTolerance2 = stepPx * 1e-6 * (stepPx * 1e-6);
  for (int it = 0; it < maxIterations; ++it) {
    const DistortionJacobian m = distortionWithJacobian(d, q);
    const double a00 = 1.0 + m.J(0, 0), a01 = m.J(0, 1), a11 = 1.0 + m.J(1, 1);
    const double fx = q.x() + m.f.x() - distortedRel.x();
    const double fy = q.y() + m.f.y() - distortedRel.y();
    const double det = a00 * a11 - a01 * a01;
    if (!(det > 1e-9) || !(a00 > 0.0)) return false;
    if (fx * fx + fy * fy < startTolerance2) return true;
    const double step_u = (a11 * fx - a01 * fy) / det;
    const double step_v = (a00 * fy - a01 * fx) / det;
    q.x() -= step_u;
    q.y() -= step_v;
    // Quadratic convergence: after a step below stepPx the error is of the order of the
    // distortion's curvature (<< 1 / px) times stepPx^2.
    if (step_u * step_u + step_v * step_v < stepPx * stepPx) return true;
  }
  return false;
}

}  // namespace imagepro
