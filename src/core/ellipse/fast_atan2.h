// atan2 to within 1e-5 rad, several times cheaper than std::atan2: enough to put a point
// on a 3-pixel arc of a traced ellipse or in one of the consensus fit's 64 angle bins.
#pragma once

#include <algorithm>
#include <cmath>

namespace imagepro {

// atan(q) for q in [0, 1] into r, an odd minimax polynomial; T is double or a vector of
// doubles (GCC vector extensions, as the trace's lanes), evaluated the same way either
// way. (By reference: a 256-bit vector passed by value would change the call's ABI.)
template <class T>
[[gnu::always_inline]] inline void atanOfRatio(const T& q, T& r) {
  const T q2 = q * q;
  r = q * (0.99997726 + q2 * (-0.33262347 + q2 * (0.19354346 + q2 * (-0.11643287 + q2 * (0.05265332 + q2 * -0.01172120)))));
}

inline double fastAtan2(double y, double x) {
  constexpr double kHalfPi = 1.57079632679489661923;
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = std::max(ax, ay), lo = std::min(ax, ay);
  if (!(hi > 0.0)) return 0.0;
  double r;
  atanOfRatio(lo / hi, r);
  if (ay > ax) r = kHalfPi - r;
  if (x < 0.0) r = 2.0 * kHalfPi - r;
  return y < 0.0 ? -r : r;
}

}  // namespace imagepro
