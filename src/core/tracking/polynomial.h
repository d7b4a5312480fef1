#pragma once
// Least-squares polynomial extrapolation of thesis 3.2.1: fit P_m(t) (eq. 3.1) to the
// last n samples by least squares (eqs. 3.2-3.3), evaluate it at the next time
// (eq. 3.4) and report the correlation coefficient r of the fit (eqs. 3.5-3.7).
#include <span>

namespace imagepro {

struct Extrapolation {
  double estimate = 0.0;  // P_m(t_next)
  double r = 1.0;         // correlation coefficient of the fit; 1 when the data are constant or fitted exactly
};

// `t` and `x` hold the samples oldest first (same length n >= 1). The degree is
// lowered to n - 1 when there are too few samples. Times are shifted and scaled
// internally so the normal equations stay well conditioned; no heap allocation.
Extrapolation extrapolatePolynomial(std::span<const double> t, std::span<const double> x, int degree,
                                    double t_next);

}  // namespace imagepro
