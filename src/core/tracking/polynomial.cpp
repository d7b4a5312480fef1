#include "core/tracking/polynomial.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace imagepro {

Extrapolation extrapolatePolynomial(std::span<const double> t, std::span<const double> x, int degree,
                                    double t_next) {
  Extrapolation out;
  const int n = static_cast<int>(std::min(t.size(), x.size()));
  if (n == 0) return out;
  const int m = std::clamp(degree, 0, std::min(3, n - 1));
  const std::size_t first = t.size() - static_cast<std::size_t>(n);

  // Centre on the newest sample and scale by the span so powers of t stay near 1.
  const double t0 = t[t.size() - 1];
  const double span = std::max(std::abs(t0 - t[first]), 1e-12);
  constexpr int kMaxRows = 128;  // the tracker keeps at most this many samples
  const int rows = std::min(n, kMaxRows);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxRows, 4> A(rows, m + 1);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxRows, 1> b(rows);
  const std::size_t start = t.size() - static_cast<std::size_t>(rows);
  for (int i = 0; i < rows; ++i) {
    const double s = (t[start + i] - t0) / span;
    double p = 1.0;
    for (int j = 0; j <= m; ++j, p *= s) A(i, j) = p;
    b(i) = x[start + i];
  }
  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1> c = A.householderQr().solve(b);

  const double sn = (t_next - t0) / span;
  double p = 1.0;
  for (int j = 0; j <= m; ++j, p *= sn) out.estimate += c(j) * p;

  // Eqs. 3.5-3.7. With m + 1 >= n the polynomial passes through every sample: r = 1.
  const double mean = b.mean();
  const double total = (b.array() - mean).square().sum();
  const double residual = (A * c - b).squaredNorm();
  if (total <= 1e-12 * std::max(1.0, mean * mean) || m + 1 >= rows) {
    out.r = 1.0;
  } else {
    out.r = std::sqrt(std::clamp((total - residual) / total, 0.0, 1.0));
  }
  return out;
}

}  // namespace imagepro
