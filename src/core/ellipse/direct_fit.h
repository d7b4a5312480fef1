#pragma once
// Direct least-squares ellipse fit (Fitzgibbon, Pilu and Fisher; thesis 2.6.2,
// eqs. 2.29-2.41) in the numerically stable form of Halir and Flusser: the scatter
// matrix S = D^T D (eq. 2.38) is split into its quadratic and linear blocks, the
// linear part of the conic is eliminated, and the constrained problem S a = lambda C a,
// a^T C a = 1 (eqs. 2.36-2.37) becomes a 3x3 eigenproblem. The points are first
// moved to their centroid and scaled to a root-mean-square distance of sqrt(2), so the
// fit is the same for a shape anywhere in the image at any size.
//
// The scatter matrix is built from the moments sum(x^i y^j), i + j <= 4, of the points
// (one pass, exact for integer pixels), so a fit costs one pass over the path plus a
// constant.
//
// Fit quality:
//  * relative_error: the thesis's E_rel = ||D a||^2 / N (eq. 2.42), with D and a in the
//    fit's normalised coordinates and a^T C a = 1. It is a relative measure (the
//    squared algebraic residual per point for a shape of unit size), so it does not
//    change with the size of the shape, but it is not affine invariant.
//  * sampson_px: the mean Sampson distance |F| / |grad F| of the points, in pixels, a
//    first-order approximation of the mean geometric distance to the ellipse.
#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <span>

#include "core/common/status.h"
#include "core/edges/edge_list.h"
#include "core/ellipse/ellipse.h"

namespace imagepro {

// Sums of x^i y^j (i + j <= 4) of a point set, relative to its first point.
struct ConicMoments {
  double origin_x = 0.0, origin_y = 0.0;
  std::size_t count = 0;
  // Index of x^i y^j is kIndex[i][j].
  std::array<double, 15> sum{};

  void clear() {
    count = 0;
    sum.fill(0.0);
  }
  void add(double x, double y);
  void add(std::span<const EdgePixel> points);
  void add(std::span<const Eigen::Vector2d> points);
};

struct EllipseFit {
  Conic conic = Conic::Zero();  // pixel coordinates, unit norm, negative inside the ellipse
  Ellipse ellipse;
  double relative_error = 0.0;  // E_rel, eq. 2.42
  double sampson_px = 0.0;      // mean Sampson distance in pixels (set by meanSampsonDistance)
  // sqrt(sum F^2 / sum |grad F|^2) in pixels (Taubin's approximation of the RMS geometric
  // distance): free from the moments, a quick screen before the per-point pass.
  double taubin_px = 0.0;
  std::size_t points = 0;
  // The fit's normalised frame, u = (x - origin) / scale, and the conic there with
  // 4ac - b^2 = 1: evaluates distances without the cancellation of the pixel form.
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  double scale = 1.0;
  Conic normalised = Conic::Zero();
};

// TooFewPoints for fewer than 6 points, DegenerateFit for collinear points or points
// that do not determine one conic, NotAnEllipse when no ellipse solves eq. 2.36 or when
// the points lie on a hyperbola or parabola (the best unconstrained conic is not an
// ellipse and fits clearly better than the best ellipse). Ok fills everything but
// sampson_px.
Status fitEllipse(const ConicMoments& moments, EllipseFit& fit);

// Mean Sampson distance of the points to the fitted conic in pixels (also stored in
// fit.sampson_px by fitEllipseDirect).
double meanSampsonDistance(const EllipseFit& fit, std::span<const EdgePixel> points);
double meanSampsonDistance(const EllipseFit& fit, std::span<const Eigen::Vector2d> points);

// Moments, fit and mean Sampson distance in one call.
Status fitEllipseDirect(std::span<const EdgePixel> points, EllipseFit& fit);
Status fitEllipseDirect(std::span<const Eigen::Vector2d> points, EllipseFit& fit);

// The signed Sampson distance of one point (pixels, negative inside the ellipse).
double sampsonDistance(const EllipseFit& fit, double x, double y);
// Its square, without the root (px^2; infinite where the conic's gradient vanishes).
double squaredSampsonDistance(const EllipseFit& fit, double x, double y);

// Whether points lie within `limit_px` (Sampson distance) of a fit's ellipse: the test
// std::abs(sampsonDistance(fit, x, y)) <= limit_px, without its division and root, for
// the loops that ask it of every point of a path many times over.
class SampsonBand {
 public:
  SampsonBand(const EllipseFit& fit, double limit_px)
      : c_(fit.normalised), inv_scale_(1.0 / fit.scale), ox_(fit.origin.x()), oy_(fit.origin.y()),
        limit2_(limit_px * limit_px * inv_scale_ * inv_scale_) {}
  bool holds(double x, double y) const {
    const double u = (x - ox_) * inv_scale_, v = (y - oy_) * inv_scale_;
    const double f = c_(0) * u * u + c_(1) * u * v + c_(2) * v * v + c_(3) * u + c_(4) * v + c_(5);
    const double gu = 2.0 * c_(0) * u + c_(1) * v + c_(3);
    const double gv = c_(1) * u + 2.0 * c_(2) * v + c_(4);
    const double g2 = gu * gu + gv * gv;
    return g2 > 0.0 && f * f <= limit2_ * g2;
  }

 private:
  Conic c_;
  double inv_scale_, ox_, oy_, limit2_;
};

}  // namespace imagepro
