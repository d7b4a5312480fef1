#include "core/ellipse/direct_fit.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "core/common/simd_level.h"
#include "core/ellipse/pixel_passes.h"

namespace imagepro {

namespace {

// Position of x^i y^j in ConicMoments::sum: by degree d = i + j, then by j.
constexpr int idx(int i, int j) {
  const int d = i + j;
  return d * (d + 1) / 2 + j;
}

constexpr double kBinomial[5][5] = {
    {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};

// The fifteen sums x^i y^j (i + j <= 4) of one point, in the order of idx(): in doubles
// for the floating-point moments, in 64-bit integers for the exact pixel sums.
template <class T>
inline void accumulate(std::array<T, 15>& s, T x, T y) {
  const T x2 = x * x, xy = x * y, y2 = y * y;
  s[0] += 1;
  s[1] += x;
  s[2] += y;
  s[3] += x2;
  s[4] += xy;
  s[5] += y2;
  s[6] += x2 * x;
  s[7] += x2 * y;
  s[8] += x * y2;
  s[9] += y2 * y;
  s[10] += x2 * x2;
  s[11] += x2 * xy;
  s[12] += x2 * y2;
  s[13] += xy * y2;
  s[14] += y2 * y2;
}

// (2^12)^4 * 2^12 = 2^60 < 2^63.
constexpr int kMomentReach = 1 << 12;
constexpr std::size_t kMomentBlock = std::size_t{1} << 12;

#if defined(__SSE2__)
// The exact integer sums of a block in doubles, two sums per instruction: with offsets below
// kExactDoubleReach, (2^10)^4 * 2^12 = 2^52, every product and partial sum is an
// integer below 2^53, so the doubles hold exactly the integer sums.
constexpr int kExactDoubleReach = 1 << 10;

void exactSums(std::span<const EdgePixel> block, int ox, int oy, std::array<double, 15>& sum) {
  const __m128i origin = _mm_setr_epi32(ox, oy, 0, 0);
  const __m128d zero = _mm_setzero_pd();
  // Lanes: (x, y), (x^2, y^2), (xy, xy), (x^3, y^3), (x^2 y, x y^2), (x^4, y^4),
  // (x^3 y, x y^3), (x^2 y^2, x^2 y^2).
  __m128d s1 = zero, s2 = zero, s11 = zero, s3 = zero, s21 = zero, s4 = zero, s31 = zero, s22 = zero;
  for (const EdgePixel& p : block) {
    const __m128d d = _mm_cvtepi32_pd(_mm_sub_epi32(pixel_passes::loadPixel(p), origin));
    const __m128d swapped = _mm_shuffle_pd(d, d, 1);
    const __m128d sq = _mm_mul_pd(d, d), xy = _mm_mul_pd(d, swapped);
    s1 = _mm_add_pd(s1, d);
    s2 = _mm_add_pd(s2, sq);
    s11 = _mm_add_pd(s11, xy);
    s3 = _mm_add_pd(s3, _mm_mul_pd(sq, d));
    s21 = _mm_add_pd(s21, _mm_mul_pd(sq, swapped));
    s4 = _mm_add_pd(s4, _mm_mul_pd(sq, sq));
    s31 = _mm_add_pd(s31, _mm_mul_pd(sq, xy));
    s22 = _mm_add_pd(s22, _mm_mul_pd(sq, _mm_shuffle_pd(sq, sq, 1)));
  }
  auto low = [](__m128d v) { return _mm_cvtsd_f64(v); };
  auto high = [](__m128d v) { return _mm_cvtsd_f64(_mm_unpackhi_pd(v, v)); };
  sum = {static_cast<double>(block.size()),
         low(s1), high(s1),
         low(s2), low(s11), high(s2),
         low(s3), low(s21), high(s21), high(s3),
         low(s4), low(s31), low(s22), high(s31), high(s4)};
}

// exactSums with two pixels per AVX2 vector, lanes (x0, y0, x1, y1): the same exact
// integer sums (so the same doubles), in half the instructions.
IMAGEPRO_AVX2_BEGIN
void exactSumsAvx2(std::span<const EdgePixel> block, int ox, int oy, std::array<double, 15>& sum) {
  const __m128i origin = _mm_setr_epi32(ox, oy, ox, oy);
  const __m256d zero = _mm256_setzero_pd();
  __m256d s1 = zero, s2 = zero, s11 = zero, s3 = zero, s21 = zero, s4 = zero, s31 = zero, s22 = zero;
  auto step = [&](__m256d d) {
    const __m256d swapped = _mm256_permute_pd(d, 0b0101);
    const __m256d sq = _mm256_mul_pd(d, d), xy = _mm256_mul_pd(d, swapped);
    s1 = _mm256_add_pd(s1, d);
    s2 = _mm256_add_pd(s2, sq);
    s11 = _mm256_add_pd(s11, xy);
    s3 = _mm256_add_pd(s3, _mm256_mul_pd(sq, d));
    s21 = _mm256_add_pd(s21, _mm256_mul_pd(sq, swapped));
    s4 = _mm256_add_pd(s4, _mm256_mul_pd(sq, sq));
    s31 = _mm256_add_pd(s31, _mm256_mul_pd(sq, xy));
    s22 = _mm256_add_pd(s22, _mm256_mul_pd(sq, _mm256_permute_pd(sq, 0b0101)));
  };
  const std::size_t n = block.size();
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    // x0 y0 gx0 gy0 x1 y1 gx1 gy1 (int16) -> x0 y0 x1 y1 (int32) -> offsets in doubles.
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(block.data() + i));
    const __m128i xy16 = _mm_shuffle_epi32(v, _MM_SHUFFLE(2, 0, 2, 0));
    step(_mm256_cvtepi32_pd(_mm_sub_epi32(_mm_cvtepi16_epi32(xy16), origin)));
  }
  if (i < n) {  // the last, odd pixel, the other lanes zero
    const __m128i p = _mm_setr_epi32(block[i].x - ox, block[i].y - oy, 0, 0);
    step(_mm256_cvtepi32_pd(p));
  }
  // Lanes 0 and 2 hold the first sum of a pair, 1 and 3 the second.
  auto first = [](__m256d v) {
    const __m128d h = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(h);
  };
  auto second = [](__m256d v) {
    const __m128d h = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(_mm_unpackhi_pd(h, h));
  };
  sum = {static_cast<double>(n),
         first(s1), second(s1),
         first(s2), first(s11), second(s2),
         first(s3), first(s21), second(s21), second(s3),
         first(s4), first(s31), first(s22), second(s31), second(s4)};
}
IMAGEPRO_AVX2_END
#endif

// Points whose best unconstrained conic is a hyperbola or parabola that fits this many
// times better (algebraic residual) than the best ellipse are reported as NotAnEllipse.
// Digitised ellipse arcs stay well below this ratio (tests: partial arcs).
constexpr double kNonEllipseResidualRatio = 4.0;
// (4ac - b^2) / (a^2 + b^2 + c^2) of the quadratic part in the normalised frame; about
// 4 / aspect^2 for a thin ellipse.
constexpr double kMinEllipseCondition = 1e-4;

}  // namespace

void ConicMoments::add(double x, double y) {
  if (count == 0) {
    origin_x = x;
    origin_y = y;
  }
  accumulate<double>(sum, x - origin_x, y - origin_y);
  ++count;
}

void ConicMoments::add(std::span<const EdgePixel> points) {
  if (points.empty()) return;
  if (count == 0) {
    origin_x = points[0].x;
    origin_y = points[0].y;
  }
  const int ox = static_cast<int>(origin_x), oy = static_cast<int>(origin_y);
  if (ox != origin_x || oy != origin_y) {  // a fractional origin from add(x, y)
    for (const EdgePixel& p : points) add(p.x, p.y);
    return;
  }
  // Exact integer sums over blocks of kMomentBlock points with offsets below
  // kMomentReach: every sum stays below 2^63. Farther points (images wider than
  // kMomentReach) take the floating-point sums.
  for (std::size_t start = 0; start < points.size(); start += kMomentBlock) {
    const std::size_t end = std::min(points.size(), start + kMomentBlock);
    const auto block = points.subspan(start, end - start);
    const pixel_passes::Bounds b = pixel_passes::bounds(block);
    const int lo = std::min({0, b.min_x - ox, b.min_y - oy}), hi = std::max({0, b.max_x - ox, b.max_y - oy});
    if (lo <= -kMomentReach || hi >= kMomentReach) {
      for (const EdgePixel& p : block) accumulate<double>(sum, p.x - ox, p.y - oy);
      continue;
    }
    std::array<double, 15> block_sum;
#if defined(__SSE2__)
    if (lo > -kExactDoubleReach && hi < kExactDoubleReach) {
      if (simdAllows(SimdLevel::Avx2))
        exactSumsAvx2(block, ox, oy, block_sum);
      else
        exactSums(block, ox, oy, block_sum);
    } else
#endif
    {
      // Sums of x^i y^j in 64-bit integers (x, y the pixels' offsets from the origin).
      std::array<std::int64_t, 15> exact{};
      for (const EdgePixel& p : block) accumulate<std::int64_t>(exact, p.x - ox, p.y - oy);
      for (int k = 0; k < 15; ++k) block_sum[k] = static_cast<double>(exact[k]);
    }
    for (int k = 0; k < 15; ++k) sum[k] += block_sum[k];
  }
  count += points.size();
}

void ConicMoments::add(std::span<const Eigen::Vector2d> points) {
  if (points.empty()) return;
  if (count == 0) {
    origin_x = points[0].x();
    origin_y = points[0].y();
  }
  // The same sums as add(x, y) point by point, kept in locals: stores into the member
  // array could alias the points and force a reload of every sum per point.
  const double ox = origin_x, oy = origin_y;
  std::array<double, 15> s = sum;
  for (const Eigen::Vector2d& p : points) accumulate<double>(s, p.x() - ox, p.y() - oy);
  sum = s;
  count += points.size();
}

Status fitEllipse(const ConicMoments& mom, EllipseFit& fit) {
  const std::size_t n = mom.count;
  if (n < 6) return Status::TooFewPoints;
  const double inv_n = 1.0 / static_cast<double>(n);
  const auto& s = mom.sum;

  // Normalising similarity: centroid to the origin, mean squared distance 2.
  const double mx = s[idx(1, 0)] * inv_n, my = s[idx(0, 1)] * inv_n;
  const double cxx = s[idx(2, 0)] * inv_n - mx * mx;
  const double cyy = s[idx(0, 2)] * inv_n - my * my;
  const double cxy = s[idx(1, 1)] * inv_n - mx * my;
  const double spread = 0.5 * (cxx + cyy);
  if (!(spread > 0.0) || !std::isfinite(spread)) return Status::DegenerateFit;
  const double scale = std::sqrt(spread);
  // Collinear points: the normalised covariance (trace 2) has a zero eigenvalue.
  if ((cxx * cyy - cxy * cxy) / (spread * spread) < 1e-10) return Status::DegenerateFit;

  // Centred, scaled moments N(i, j) = sum(u^i v^j) by binomial expansion.
  double nm[5][5] = {};
  const double pmx[5] = {1, -mx, mx * mx, -mx * mx * mx, mx * mx * mx * mx};
  const double pmy[5] = {1, -my, my * my, -my * my * my, my * my * my * my};
  // By degree: every N(i, j) of one degree divides by the same power of the scale,
  // computed once (by std::pow; products of the scale would round differently).
  for (int degree = 0; degree <= 4; ++degree) {
    const double scale_power = std::pow(scale, degree);
    for (int i = 0; i <= degree; ++i) {
      const int j = degree - i;
      double acc = 0.0;
      for (int p = 0; p <= i; ++p)
        for (int q = 0; q <= j; ++q)
          acc += kBinomial[i][p] * kBinomial[j][q] * pmx[i - p] * pmy[j - q] * s[idx(p, q)];
      nm[i][j] = acc / scale_power;
    }
  }
  nm[1][0] = nm[0][1] = 0.0;  // exact by construction

  // Scatter blocks (Halir-Flusser): quadratic monomials (u^2, uv, v^2), linear (u, v, 1).
  Eigen::Matrix3d S1, S2, S3;
  S1 << nm[4][0], nm[3][1], nm[2][2],  //
      nm[3][1], nm[2][2], nm[1][3],    //
      nm[2][2], nm[1][3], nm[0][4];
  S2 << nm[3][0], nm[2][1], nm[2][0],  //
      nm[2][1], nm[1][2], nm[1][1],    //
      nm[1][2], nm[0][3], nm[0][2];
  S3 << nm[2][0], nm[1][1], 0.0,  //
      nm[1][1], nm[0][2], 0.0,    //
      0.0, 0.0, nm[0][0];
  const Eigen::Matrix3d T = -S3.inverse() * S2.transpose();  // linear part = T * quadratic part
  Eigen::Matrix3d M = S1 + S2 * T;                            // reduced scatter matrix
  M = 0.5 * (M + M.transpose()).eval();
  const double trace = M.trace();
  if (!std::isfinite(trace)) return Status::DegenerateFit;

  // The best conic without the ellipse constraint (unit quadratic part): if the points
  // leave more than one conic free, the fit is degenerate.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> sym;
  sym.computeDirect(M);
  const Eigen::Vector3d sym_values = sym.eigenvalues();
  if (sym_values(1) <= 1e-12 * std::max(trace, std::numeric_limits<double>::min()))
    return Status::DegenerateFit;

  // M a1 = lambda C1 a1 with C1 the upper 3x3 block of C (eq. 2.34); the solution is the
  // eigenvector with 4ac - b^2 > 0, the one positive lambda.
  Eigen::Vector3d a1;
  int best = -1;
  if (sym_values(0) > 1e-8 * trace) {
    // M positive definite (every real contour): with M = L L^T the pencil becomes the
    // symmetric L^-1 C1 L^-T y = (1 / lambda) y, a1 = L^-T y, and the solution belongs
    // to its largest eigenvalue.
    const Eigen::LLT<Eigen::Matrix3d> llt(M);
    Eigen::Matrix3d C1;
    C1 << 0, 0, 2, 0, -1, 0, 2, 0, 0;
    const auto L = llt.matrixL();
    const Eigen::Matrix3d B = L.solve(C1);                         // L^-1 C1
    Eigen::Matrix3d A = L.solve(B.transpose()).transpose();        // L^-1 C1 L^-T
    A = 0.5 * (A + A.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pencil;
    pencil.computeDirect(A);
    const Eigen::Vector3d v = llt.matrixU().solve(Eigen::Vector3d(pencil.eigenvectors().col(2)));
    const double cond = 4.0 * v(0) * v(2) - v(1) * v(1);
    if (llt.info() == Eigen::Success && pencil.eigenvalues()(2) > 0.0 && cond > 1e-12 * v.squaredNorm()) {
      a1 = v / std::sqrt(cond);  // a^T C a = 1 (eq. 2.37)
      best = 2;
    }
  }
  if (best < 0) {
    // Points on an exact conic (M singular): eigenvectors of C1^-1 M.
    Eigen::Matrix3d CinvM;
    CinvM.row(0) = 0.5 * M.row(2);
    CinvM.row(1) = -M.row(1);
    CinvM.row(2) = 0.5 * M.row(0);
    Eigen::EigenSolver<Eigen::Matrix3d> es(CinvM);
    if (es.info() != Eigen::Success) return Status::DegenerateFit;
    double best_residual = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (std::abs(es.eigenvalues()(k).imag()) > 1e-9 * std::abs(es.eigenvalues()(k).real()) + 1e-300)
        continue;
      const Eigen::Vector3d v = es.eigenvectors().col(k).real();
      const double cond = 4.0 * v(0) * v(2) - v(1) * v(1);
      if (!(cond > 1e-12 * v.squaredNorm())) continue;
      const double residual = v.dot(M * v) / cond;
      if (residual < best_residual) {
        best_residual = residual;
        best = k;
        a1 = v / std::sqrt(cond);
      }
    }
  }
  if (best < 0) return Status::NotAnEllipse;

  // Hyperbola or parabola data: the unconstrained optimum is not an ellipse (a parabola
  // within rounding) and either explains the points far better than the best ellipse or
  // leaves only a degenerate, needle-thin best ellipse (aspect ratio beyond ~200).
  {
    const Eigen::Vector3d v = sym.eigenvectors().col(0);
    const bool free_is_ellipse = 4.0 * v(0) * v(2) - v(1) * v(1) > 1e-6 * v.squaredNorm();
    const double ellipse_residual = a1.dot(M * a1) / a1.squaredNorm();
    const double ellipse_condition = 1.0 / a1.squaredNorm();  // (4ac - b^2) / |a1|^2
    if (!free_is_ellipse &&
        (ellipse_residual > kNonEllipseResidualRatio * std::max(sym_values(0), 0.0) + 1e-13 * trace ||
         ellipse_condition < kMinEllipseCondition))
      return Status::NotAnEllipse;
  }

  const Eigen::Vector3d a2 = T * a1;
  Conic an;
  an << a1, a2;
  Ellipse en;
  if (!ellipseFromConic(an, en)) return Status::NotAnEllipse;

  // Back to pixels: u = (x - x0) / scale.
  const double x0 = mom.origin_x + mx, y0 = mom.origin_y + my;
  const double is = 1.0 / scale, is2 = is * is;
  const double A = an(0), B = an(1), C = an(2), D = an(3), E = an(4), F = an(5);
  Conic cp;
  cp << A * is2, B * is2, C * is2,                      //
      D * is - (2.0 * A * x0 + B * y0) * is2,           //
      E * is - (B * x0 + 2.0 * C * y0) * is2,           //
      (A * x0 * x0 + B * x0 * y0 + C * y0 * y0) * is2 - (D * x0 + E * y0) * is + F;
  if (cp(0) + cp(2) < 0.0) cp = -cp;
  fit.conic = cp / cp.norm();
  fit.ellipse.cx = x0 + scale * en.cx;
  fit.ellipse.cy = y0 + scale * en.cy;
  fit.ellipse.a = scale * en.a;
  fit.ellipse.b = scale * en.b;
  fit.ellipse.angle_deg = en.angle_deg;
  const double residual = std::max(0.0, a1.dot(M * a1));
  fit.relative_error = residual * inv_n;  // eq. 2.42
  const double gradient = (4.0 * A * A + B * B) * nm[2][0] + (B * B + 4.0 * C * C) * nm[0][2] +
                          4.0 * B * (A + C) * nm[1][1] + (D * D + E * E) * nm[0][0];
  fit.taubin_px = gradient > 0.0 ? scale * std::sqrt(residual / gradient) : 0.0;
  fit.sampson_px = 0.0;
  fit.points = n;
  fit.origin = {x0, y0};
  fit.scale = scale;
  // Orient so that the conic is negative inside (the quadratic part is positive definite).
  fit.normalised = (an(0) + an(2) < 0.0) ? Conic(-an) : an;
  return Status::Ok;
}

namespace {
// The conic's value f and its gradient's squared length at (x, y), in the fit's normalised frame.
struct ConicAt {
  double f, g2;
};
ConicAt conicAt(const EllipseFit& fit, double x, double y) {
  const Conic& c = fit.normalised;
  const double is = 1.0 / fit.scale;
  const double u = (x - fit.origin.x()) * is, v = (y - fit.origin.y()) * is;
  const double gu = 2.0 * c(0) * u + c(1) * v + c(3);
  const double gv = c(1) * u + 2.0 * c(2) * v + c(4);
  return {c(0) * u * u + c(1) * u * v + c(2) * v * v + c(3) * u + c(4) * v + c(5), gu * gu + gv * gv};
}
}  // namespace

double sampsonDistance(const EllipseFit& fit, double x, double y) {
  const auto [f, g2] = conicAt(fit, x, y);
  const double g = std::sqrt(g2);
  if (!(g > 0.0)) return f < 0.0 ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  return fit.scale * f / g;
}

double squaredSampsonDistance(const EllipseFit& fit, double x, double y) {
  const auto [f, g2] = conicAt(fit, x, y);
  if (!(g2 > 0.0)) return std::numeric_limits<double>::infinity();
  return fit.scale * fit.scale * f * f / g2;
}

namespace {
template <class Points, class Get>
double meanSampson(const EllipseFit& fit, const Points& points, Get get) {
  if (points.empty()) return 0.0;
  const Conic& c = fit.normalised;
  const double is = 1.0 / fit.scale;
  const double ox = fit.origin.x(), oy = fit.origin.y();
  double total = 0.0;
  for (const auto& p : points) {
    const auto [x, y] = get(p);
    const double u = (x - ox) * is, v = (y - oy) * is;
    const double f = c(0) * u * u + c(1) * u * v + c(2) * v * v + c(3) * u + c(4) * v + c(5);
    const double gu = 2.0 * c(0) * u + c(1) * v + c(3);
    const double gv = c(1) * u + 2.0 * c(2) * v + c(4);
    const double g2 = gu * gu + gv * gv;
    // A point at the centre (zero gradient) is as far as the ellipse's minor semi-axis.
    total += g2 > 0.0 ? std::abs(f) / std::sqrt(g2) : fit.ellipse.b * is;
  }
  return fit.scale * total / static_cast<double>(points.size());
}
}  // namespace

double meanSampsonDistance(const EllipseFit& fit, std::span<const EdgePixel> points) {
  return meanSampson(fit, points, [](const EdgePixel& p) {
    return std::pair<double, double>{p.x, p.y};
  });
}

double meanSampsonDistance(const EllipseFit& fit, std::span<const Eigen::Vector2d> points) {
  return meanSampson(fit, points, [](const Eigen::Vector2d& p) {
    return std::pair<double, double>{p.x(), p.y()};
  });
}

Status fitEllipseDirect(std::span<const EdgePixel> points, EllipseFit& fit) {
  ConicMoments m;
  m.add(points);
  const Status st = fitEllipse(m, fit);
  if (ok(st)) fit.sampson_px = meanSampsonDistance(fit, points);
  return st;
}

Status fitEllipseDirect(std::span<const Eigen::Vector2d> points, EllipseFit& fit) {
  ConicMoments m;
  m.add(points);
  const Status st = fitEllipse(m, fit);
  if (ok(st)) fit.sampson_px = meanSampsonDistance(fit, points);
  return st;
}

}  // namespace imagepro
