#include "core/reconstruction/undistort.h"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace imagepro {

namespace {
constexpr double kExactStepPx = 1e-12;  // machine precision on an image's coordinates
}  // namespace

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
  Eigen::Vector2d y = undistortTaylor(cam, distortedPx) - c;
  // Beyond the fold of the model, or unconverged, the last iterate is kept.
  invertDistortion(cam.distortion, distortedPx - c, y, maxIterations, kExactStepPx);
  return y + c;
}

namespace {

#if defined(__SSE2__)
// undistortTaylor for two points at once, one per lane, in the very operations and order of
// distortionWithJacobian (lens_model.cpp) and undistortTaylor above (the same results to the bit).
void undistortTaylorPair(const CameraModel& cam, double* a, double* b) {
  const Distortion& d = cam.distortion;
  auto all = [](double x) { return _mm_set1_pd(x); };
  const __m128d pa = _mm_loadu_pd(a), pb = _mm_loadu_pd(b);  // (x, y) of each point
  const __m128d x = _mm_unpacklo_pd(pa, pb), y = _mm_unpackhi_pd(pa, pb);
  const __m128d u = _mm_sub_pd(x, all(cam.u0())), v = _mm_sub_pd(y, all(cam.v0()));
  const __m128d two = all(2.0);
  const __m128d uu = _mm_mul_pd(u, u), vv = _mm_mul_pd(v, v), uv = _mm_mul_pd(u, v);
  const __m128d r2 = _mm_add_pd(uu, vv);
  const __m128d radial = _mm_add_pd(_mm_mul_pd(all(d.k1), r2), _mm_mul_pd(_mm_mul_pd(all(d.k2), r2), r2));
  const __m128d dRadialCoef = _mm_mul_pd(two, _mm_add_pd(all(d.k1), _mm_mul_pd(_mm_mul_pd(two, all(d.k2)), r2)));
  const __m128d p1x2 = _mm_mul_pd(two, all(d.p1)), p2x2 = _mm_mul_pd(two, all(d.p2));
  const __m128d fu = _mm_add_pd(_mm_add_pd(_mm_mul_pd(u, radial), _mm_mul_pd(p1x2, uv)),
                                _mm_mul_pd(all(d.p2), _mm_add_pd(r2, _mm_mul_pd(two, uu))));
  const __m128d fv = _mm_add_pd(_mm_add_pd(_mm_mul_pd(v, radial), _mm_mul_pd(all(d.p1), _mm_add_pd(r2, _mm_mul_pd(two, vv)))),
                                _mm_mul_pd(p2x2, uv));
  const __m128d cross =
      _mm_add_pd(_mm_add_pd(_mm_mul_pd(uv, dRadialCoef), _mm_mul_pd(p1x2, u)), _mm_mul_pd(p2x2, v));
  const __m128d fu_u = _mm_add_pd(_mm_add_pd(_mm_add_pd(radial, _mm_mul_pd(uu, dRadialCoef)), _mm_mul_pd(p1x2, v)),
                                  _mm_mul_pd(_mm_mul_pd(all(6.0), all(d.p2)), u));
  const __m128d fv_v = _mm_add_pd(
      _mm_add_pd(_mm_add_pd(radial, _mm_mul_pd(vv, dRadialCoef)), _mm_mul_pd(_mm_mul_pd(all(6.0), all(d.p1)), v)),
      _mm_mul_pd(p2x2, u));
  const __m128d denominator = _mm_add_pd(_mm_add_pd(all(1.0), fu_u), fv_v);
  const __m128d sign = all(-0.0);  // negation flips the sign bit, as the scalar -f does
  const __m128d minusFu = _mm_xor_pd(fu, sign), minusFv = _mm_xor_pd(fv, sign);
  const __m128d xs = _mm_add_pd(
      x, _mm_div_pd(_mm_sub_pd(_mm_add_pd(minusFu, _mm_mul_pd(fv, cross)), _mm_mul_pd(fu, fv_v)), denominator));
  const __m128d ys = _mm_add_pd(
      y, _mm_div_pd(_mm_sub_pd(_mm_add_pd(minusFv, _mm_mul_pd(fu, cross)), _mm_mul_pd(fv, fu_u)), denominator));
  _mm_storeu_pd(a, _mm_unpacklo_pd(xs, ys));
  _mm_storeu_pd(b, _mm_unpackhi_pd(xs, ys));
}
#endif

}  // namespace

void undistortPoints(const CameraModel& cam, bool exact, std::span<Eigen::Vector2d> points) {
  if (cam.distortion.isZero()) return;
  if (exact) {
    for (Eigen::Vector2d& p : points) p = undistortExact(cam, p);
    return;
  }
  std::size_t i = 0;
#if defined(__SSE2__)
  for (; i + 2 <= points.size(); i += 2) undistortTaylorPair(cam, points[i].data(), points[i + 1].data());
#endif
  for (; i < points.size(); ++i) points[i] = undistortTaylor(cam, points[i]);
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
      e.largest_displacement_px = std::max(e.largest_displacement_px, (truth - x).norm());
      const double err = (undistortTaylor(cam, x) - truth).norm();
      e.max_px = std::max(e.max_px, err);
      sum2 += err * err;
      const auto ring = static_cast<std::size_t>(std::hypot(u - cam.u0(), v - cam.v0()));
      if (ring >= e.max_px_by_radius.size()) e.max_px_by_radius.resize(ring + 1, 0.0);
      e.max_px_by_radius[ring] = std::max(e.max_px_by_radius[ring], err);
    }
  }
  const double n = static_cast<double>(cam.width) * cam.height;
  e.rms_px = n > 0 ? std::sqrt(sum2 / n) : 0.0;
  return e;
}

namespace {

bool sameLens(const CameraModel& a, const CameraModel& b) {
  return a.width == b.width && a.height == b.height && a.principal_point_px == b.principal_point_px &&
         a.distortion.k1 == b.distortion.k1 && a.distortion.k2 == b.distortion.k2 &&
         a.distortion.p1 == b.distortion.p1 && a.distortion.p2 == b.distortion.p2;
}

double taylorErrorAt(const CameraModel& cam, int u, int v) {
  const Eigen::Vector2d x(u, v);
  return (undistortTaylor(cam, x) - undistortExact(cam, x)).norm();
}

}  // namespace

const char* lensInverseName(LensInverse inverse) {
  switch (inverse) {
    case LensInverse::None: return "none";
    case LensInverse::Taylor: return "taylor";
    case LensInverse::Exact: return "exact";
    case LensInverse::ExactWideLens: return "exact-wide-lens";
  }
  return "none";
}

double taylorInverseErrorPx(const CameraModel& cam) {
  thread_local CameraModel last;
  thread_local double error = -1.0;
  if (error >= 0.0 && sameLens(cam, last)) return error;
  double most = 0.0;
  if (!cam.distortion.isZero() && cam.width > 0 && cam.height > 0) {
    const int w = cam.width - 1, h = cam.height - 1;
    for (int u = 0; u <= w; ++u) most = std::max({most, taylorErrorAt(cam, u, 0), taylorErrorAt(cam, u, h)});
    for (int v = 0; v <= h; ++v) most = std::max({most, taylorErrorAt(cam, 0, v), taylorErrorAt(cam, w, v)});
    for (int v = 16; v < h; v += 16)
      for (int u = 16; u < w; u += 16) most = std::max(most, taylorErrorAt(cam, u, v));
  }
  last = cam;
  error = most;
  return error;
}

}  // namespace imagepro
