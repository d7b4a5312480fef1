#include "core/analysis/pendulum.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace imagepro {

namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

// Least-squares sinusoid s ~ c + a cos(w t) + b sin(w t) at a fixed angular frequency.
struct SineFit {
  double c = 0.0, a = 0.0, b = 0.0;
  double rss = 0.0;
  bool ok = false;
  double amplitude() const { return std::hypot(a, b); }
};

SineFit fitSine(std::span<const double> t, std::span<const double> s, double omega) {
  Eigen::Matrix3d N = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Eigen::Vector3d x(1.0, std::cos(omega * t[i]), std::sin(omega * t[i]));
    N.noalias() += x * x.transpose();
    r += x * s[i];
  }
  SineFit f;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(N);
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12)) return f;
  const Eigen::Vector3d p = ldlt.solve(r);
  f.c = p[0];
  f.a = p[1];
  f.b = p[2];
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double e = s[i] - (f.c + f.a * std::cos(omega * t[i]) + f.b * std::sin(omega * t[i]));
    f.rss += e * e;
  }
  f.ok = true;
  return f;
}

// The angular frequency whose sinusoid explains most of s: a scan at a quarter of the
// record's frequency resolution, then golden-section refinement around the best. The
// scan's sines and cosines come from one rotation per sample and frequency step, so it
// costs a few multiply-adds per sample and frequency (no subsampling, so no aliases).
// A record with long gaps (frames missing, or a timestamp far off) would ask for more
// frequencies than its samples can tell apart, and memory for each: the scan then takes
// coarser steps, at most this many per sample (an even record needs about two).
constexpr double kMaxScanStepsPerSample = 4.0;

double bestSineOmega(std::span<const double> t, std::span<const double> s, double min_hz, double max_hz) {
  const double duration = t.back() - t.front();
  double span_hz = max_hz - min_hz;
  if (!std::isfinite(span_hz) || span_hz < 0.0) span_hz = 0.0;
  const double max_steps = kMaxScanStepsPerSample * static_cast<double>(t.size()) + 64.0;
  double step_hz = 1.0 / (4.0 * duration);
  if (!(step_hz > 0.0) || !std::isfinite(step_hz) || span_hz / step_hz > max_steps) step_hz = span_hz / max_steps;
  const std::size_t steps = step_hz > 0.0 ? static_cast<std::size_t>(span_hz / step_hz) + 1 : 1;
  // Per frequency: sums of cc, ss, sc, c, s, y c, y s.
  std::vector<std::array<double, 7>> sums(steps, std::array<double, 7>{});
  double n = 0.0, sum_y = 0.0, sum_yy = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    double c = std::cos(2.0 * M_PI * min_hz * t[i]), sn = std::sin(2.0 * M_PI * min_hz * t[i]);
    const double cd = std::cos(2.0 * M_PI * step_hz * t[i]), sd = std::sin(2.0 * M_PI * step_hz * t[i]);
    const double y = s[i];
    n += 1.0;
    sum_y += y;
    sum_yy += y * y;
    for (std::array<double, 7>& a : sums) {
      a[0] += c * c;
      a[1] += sn * sn;
      a[2] += sn * c;
      a[3] += c;
      a[4] += sn;
      a[5] += y * c;
      a[6] += y * sn;
      const double next_c = c * cd - sn * sd;
      sn = sn * cd + c * sd;
      c = next_c;
    }
  }
  double best_hz = min_hz, best_rss = INFINITY;
  for (std::size_t k = 0; k < steps; ++k) {
    const std::array<double, 7>& a = sums[k];
    Eigen::Matrix3d N;
    N << n, a[3], a[4], a[3], a[0], a[2], a[4], a[2], a[1];
    const Eigen::Vector3d r(sum_y, a[5], a[6]);
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(N);
    if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12)) continue;
    const double rss = sum_yy - r.dot(ldlt.solve(r));  // residual of the least-squares fit
    if (rss < best_rss) {
      best_rss = rss;
      best_hz = min_hz + static_cast<double>(k) * step_hz;
    }
  }
  auto rss = [&](double f) {
    const SineFit fit = fitSine(t, s, 2.0 * M_PI * f);
    return fit.ok ? fit.rss : INFINITY;
  };
  constexpr double kInvPhi = 0.6180339887498949;
  double lo = std::max(best_hz - step_hz, 0.5 * min_hz), hi = best_hz + step_hz;
  double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  double r1 = rss(x1), r2 = rss(x2);
  for (int it = 0; it < 60 && hi - lo > 1e-9 * best_hz; ++it) {
    if (r1 < r2) {
      hi = x2;
      x2 = x1;
      r2 = r1;
      x1 = hi - kInvPhi * (hi - lo);
      r1 = rss(x1);
    } else {
      lo = x1;
      x1 = x2;
      r1 = r2;
      x2 = lo + kInvPhi * (hi - lo);
      r2 = rss(x2);
    }
  }
  return 2.0 * M_PI * 0.5 * (lo + hi);
}

// Time in [t[i], t[i+1]] where the samples, less `level`, cross zero: the root of the
// cubic through the four samples around (Newton from the straight line), or of the
// straight line when there are no neighbours close enough.
double crossingTime(std::span<const double> t, std::span<const double> s, std::size_t i, double level,
                    double max_span) {
  const double a = s[i] - level, b = s[i + 1] - level;
  const double linear = t[i] + (t[i + 1] - t[i]) * a / (a - b);
  if (i == 0 || i + 2 >= t.size() || t[i + 2] - t[i - 1] > max_span) return linear;
  const double tx[4] = {t[i - 1], t[i], t[i + 1], t[i + 2]};
  const double sx[4] = {s[i - 1] - level, a, b, s[i + 2] - level};
  // Lagrange form: value and derivative at x.
  auto cubic = [&](double x, double& slope) {
    double value = 0.0;
    slope = 0.0;
    for (int j = 0; j < 4; ++j) {
      double basis = 1.0, dbasis = 0.0;
      for (int m = 0; m < 4; ++m) {
        if (m == j) continue;
        const double denom = tx[j] - tx[m];
        dbasis = dbasis * (x - tx[m]) / denom + basis / denom;
        basis *= (x - tx[m]) / denom;
      }
      value += sx[j] * basis;
      slope += sx[j] * dbasis;
    }
    return value;
  };
  double x = linear;
  for (int it = 0; it < 8; ++it) {
    double slope = 0.0;
    const double value = cubic(x, slope);
    if (!(std::abs(slope) > 0.0)) return linear;
    const double next = x - value / slope;
    if (!(next >= t[i] && next <= t[i + 1])) return linear;  // not the crossing in between
    if (std::abs(next - x) < 1e-12) return next;
    x = next;
  }
  return x;
}

struct Crossing {
  double t = 0.0;
  bool rising = false;
  long k = 0;  // half-swing number
};

// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean.
double ellipticK(double k) {
  double a = 1.0, b = std::sqrt(std::max(0.0, 1.0 - k * k));
  for (int i = 0; i < 40 && std::abs(a - b) > 1e-16 * a; ++i) {
    const double next_a = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next_a;
  }
  return M_PI / (2.0 * a);
}

}  // namespace

double pendulumPeriodFactor(double amplitude_rad) {
  const double k = std::sin(0.5 * std::min(std::abs(amplitude_rad), 0.999 * M_PI));
  return 2.0 * ellipticK(k) / M_PI;
}

Status estimatePeriod(std::span<const double> times_s, std::span<const Eigen::Vector3d> positions_mm,
                      PeriodEstimate& out) {
  out = PeriodEstimate{};
  const std::size_t n = times_s.size();
  if (positions_mm.size() != n) return Status::DegenerateFit;
  if (n < static_cast<std::size_t>(kPendulumMinFrames)) return Status::TooFewFrames;
  for (std::size_t i = 1; i < n; ++i)
    if (!(times_s[i] > times_s[i - 1])) return Status::DegenerateFit;
  for (const Eigen::Vector3d& p : positions_mm)
    if (!p.allFinite()) return Status::DegenerateFit;

  // Swing direction: principal axis of the positions.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : positions_mm) mean += p;
  mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : positions_mm) cov.noalias() += (p - mean) * (p - mean).transpose();
  cov /= static_cast<double>(n);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(cov);
  const double spread = std::sqrt(std::max(0.0, eigen.eigenvalues()[2]));
  if (!(spread > 1e-9 * std::max(1.0, mean.norm()))) return Status::NoSwing;
  out.direction = eigen.eigenvectors().col(2).normalized();

  std::vector<double> t(n), s(n);
  const double t0 = times_s[0];
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = times_s[i] - t0;  // well-conditioned phases
    s[i] = out.direction.dot(positions_mm[i] - mean);
  }
  // Sampling interval: the median spacing (frames may be missing).
  std::vector<double> gaps(n - 1);
  for (std::size_t i = 1; i < n; ++i) gaps[i - 1] = t[i] - t[i - 1];
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<long>(gaps.size() / 2), gaps.end());
  const double dt = gaps[gaps.size() / 2];
  const double duration = t.back();

  // Oscillation test and swing numbering: the best sinusoid of at least one period in
  // the record, at most the Nyquist frequency.
  const double omega = bestSineOmega(t, s, 1.0 / duration, 0.5 / dt);
  const SineFit sine = fitSine(t, s, omega);
  double tss = 0.0;
  for (double v : s) tss += v * v;  // s has zero mean
  out.sine_fraction = sine.ok && tss > 0.0 ? std::max(0.0, 1.0 - sine.rss / tss) : 0.0;
  out.amplitude_mm = sine.amplitude();
  // Noise alone fits some sinusoid too, the better the fewer the samples.
  if (!sine.ok || out.sine_fraction < std::max(0.5, 8.0 / static_cast<double>(n))) return Status::NoSwing;
  const double guess = 2.0 * M_PI / omega;

  // Crossings of the mid-swing level, each counted once the motion has gone beyond a
  // third of the amplitude since the last one (noise near the level is not a crossing),
  // and only across a gap short enough to interpolate.
  const double level = sine.c;
  const double hysteresis = out.amplitude_mm / 3.0;
  std::vector<Crossing> crossings;
  bool armed = std::abs(s[0] - level) > hysteresis;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double a = s[i] - level, b = s[i + 1] - level;
    if (armed && (a < 0.0) != (b < 0.0) && t[i + 1] - t[i] <= 0.25 * guess) {
      Crossing c;
      c.t = crossingTime(t, s, i, level, 0.5 * guess);
      c.rising = b > a;
      crossings.push_back(c);
      armed = false;
    }
    if (std::abs(b) > hysteresis) armed = true;
  }
  if (crossings.size() < 4) return Status::NoSwing;  // not even one and a half swings

  // Half-swing numbers: successive crossings half a period apart, and a rising and a
  // falling crossing an odd number of half periods apart.
  for (std::size_t j = 1; j < crossings.size(); ++j) {
    const double halves = (crossings[j].t - crossings[j - 1].t) / (0.5 * guess);
    long step = std::max(1L, std::lround(halves));
    const bool odd = crossings[j].rising != crossings[j - 1].rising;
    if ((step % 2 == 1) != odd) step += (halves > static_cast<double>(step) || step == 1) ? 1 : -1;
    crossings[j].k = crossings[j - 1].k + step;
  }
  // t_j = t_rising [rising] + t_falling [falling] + k_j H, H = T / 2.
  const bool both = std::any_of(crossings.begin(), crossings.end(), [](const Crossing& c) { return c.rising; }) &&
                    std::any_of(crossings.begin(), crossings.end(), [](const Crossing& c) { return !c.rising; });
  const int params = both ? 3 : 2;
  const std::size_t m = crossings.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<long>(m), params);
  Eigen::VectorXd y(static_cast<long>(m));
  for (std::size_t j = 0; j < m; ++j) {
    const long row = static_cast<long>(j);
    A(row, 0) = static_cast<double>(crossings[j].k);
    A(row, 1) = both ? (crossings[j].rising ? 1.0 : 0.0) : 1.0;
    if (both) A(row, 2) = crossings[j].rising ? 0.0 : 1.0;
    y[row] = crossings[j].t;
  }
  const Eigen::MatrixXd normal = A.transpose() * A;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return Status::DegenerateFit;
  const Eigen::VectorXd p = ldlt.solve(A.transpose() * y);
  const double rss = (A * p - y).squaredNorm();
  const double variance = rss / static_cast<double>(static_cast<long>(m) - params);
  const Eigen::MatrixXd inverse = ldlt.solve(Eigen::MatrixXd::Identity(params, params));
  out.period_s = 2.0 * p[0];
  out.period_sigma_s = 2.0 * std::sqrt(std::max(0.0, variance * inverse(0, 0)));
  out.crossings = static_cast<int>(m);
  if (!(out.period_s > 0.0) || !std::isfinite(out.period_sigma_s)) return Status::DegenerateFit;
  return Status::Ok;
}

Status estimatePeriodByMaxima(std::span<const double> times_s, std::span<const Eigen::Vector3d> positions_mm,
                              double swing_period_s, MaximaPeriod& out) {
  out = MaximaPeriod{};
  const std::size_t n = times_s.size();
  if (positions_mm.size() != n || !(swing_period_s > 0.0)) return Status::DegenerateFit;
  if (n < static_cast<std::size_t>(kPendulumMinFrames)) return Status::TooFewFrames;
  for (std::size_t i = 1; i < n; ++i)
    if (!(times_s[i] > times_s[i - 1])) return Status::DegenerateFit;
  std::vector<double> t(n), s(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = times_s[i] - times_s[0];
  const double dt = t.back() / static_cast<double>(n - 1);  // mean frame time
  const double omega = 2.0 * M_PI / swing_period_s;
  double sum = 0.0, sum_sq = 0.0, frame_share = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    double mean = 0.0;
    for (std::size_t i = 0; i < n; ++i) mean += positions_mm[i][axis];
    mean /= static_cast<double>(n);
    double tss = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      s[i] = positions_mm[i][axis] - mean;
      tss += s[i] * s[i];
    }
    const SineFit sine = fitSine(t, s, omega);
    if (!sine.ok || !(tss > 0.0) || 1.0 - sine.rss / tss < 0.5) continue;
    const double level = sine.c, band = sine.amplitude() / 3.0;
    // A maximum: a frame above the band that is the highest within a quarter period
    // either side (so one a cycle), with frames on both sides of it (the record's first
    // and last two frames are not).
    std::vector<double> maxima;
    const double quarter = 0.25 * swing_period_s;
    std::size_t from = 0, to = 0;  // the window [from, to) about frame i
    for (std::size_t i = 2; i + 2 < n; ++i) {
      while (t[from] < t[i] - quarter) ++from;
      while (to < n && t[to] <= t[i] + quarter) ++to;
      if (!(s[i] > level + band)) continue;
      bool highest = true;
      for (std::size_t j = from; j < to && highest; ++j) highest = s[j] < s[i] || (s[j] == s[i] && j >= i);
      if (highest) maxima.push_back(t[i]);
    }
    if (maxima.size() < 2) continue;
    const int cycles = static_cast<int>(maxima.size()) - 1;
    const double period = (maxima.back() - maxima.front()) / cycles;
    out.axis_period_s[axis] = period;
    out.axis_cycles[axis] = cycles;
    ++out.axes;
    sum += period;
    sum_sq += period * period;
    frame_share = std::max(frame_share, dt / (std::sqrt(6.0) * cycles));
  }
  if (out.axes == 0) return Status::NoSwing;
  out.period_s = sum / out.axes;
  const double spread =
      out.axes > 1 ? std::sqrt(std::max(0.0, (sum_sq - out.axes * out.period_s * out.period_s) / (out.axes - 1))) : 0.0;
  out.period_sigma_s = std::max(spread / std::sqrt(static_cast<double>(out.axes)), frame_share);
  return Status::Ok;
}

Status fitConstrainedSphere(std::span<const Eigen::Vector3d> positions_mm, std::span<const Eigen::Vector3d> normals,
                            SphereFit& out) {
  out = SphereFit{};
  const std::size_t n = positions_mm.size();
  if (normals.size() != n) return Status::DegenerateFit;
  if (n < 4) return Status::TooFewFrames;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : positions_mm) mean += p;
  mean /= static_cast<double>(n);
  std::vector<Eigen::Vector3d> p(n);  // about the mean position: the same equations, better conditioned
  for (std::size_t i = 0; i < n; ++i) p[i] = positions_mm[i] - mean;

  // Eq. 5.6 by pseudo-inverse, as in the thesis: unknowns (a, b, c, r^2 - a^2 - b^2 - c^2).
  const long rows = static_cast<long>(2 * n);
  Eigen::MatrixXd A(rows, 4);
  Eigen::VectorXd y(rows);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& u = normals[i];
    const long r = static_cast<long>(2 * i);
    A.row(r) << 2.0 * p[i].x(), 2.0 * p[i].y(), 2.0 * p[i].z(), 1.0;
    y[r] = p[i].squaredNorm();
    A.row(r + 1) << u.x(), u.y(), u.z(), 0.0;
    y[r + 1] = u.dot(p[i]);
  }
  if (!A.allFinite() || !y.allFinite()) return Status::DegenerateFit;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 4) return Status::DegenerateFit;
  const Eigen::Vector4d algebraic = qr.solve(y);
  const double r2 = algebraic[3] + algebraic.head<3>().squaredNorm();
  if (!algebraic.allFinite() || !(r2 > 0.0)) return Status::DegenerateFit;

  // The algebraic solution weighs far points more and is biased for short arcs; from it,
  // Gauss-Newton on geometric residuals: |p - centre| - radius in millimetres (eq. 5.2)
  // and the cosine of the angle between the radius vector and u3 (eq. 5.3 divided by
  // |p - centre|: a noisy normal times the long radius vector would otherwise pull the
  // centre towards the points), each kind weighted by the inverse of its RMS.
  Eigen::Vector4d x;  // centre (about the mean), radius
  x << algebraic.head<3>(), std::sqrt(r2);
  Eigen::MatrixXd J(rows, 4);
  Eigen::VectorXd e(rows), w(rows);
  double radial_rms = 0.0, angle_rms = 0.0;
  auto evaluate = [&](const Eigen::Vector4d& at) {
    double radial = 0.0, angle = 0.0, along_normal = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const long r = static_cast<long>(2 * i);
      const Eigen::Vector3d v = p[i] - at.head<3>();
      const Eigen::Vector3d& u = normals[i];
      const double d = v.norm();
      if (!(d > 0.0)) return false;
      J.row(r) << -v.transpose() / d, -1.0;
      e[r] = d - at[3];
      const double uv = u.dot(v);
      J.row(r + 1) << (u / d - uv * v / (d * d * d)).transpose(), 0.0;
      e[r + 1] = -uv / d;
      radial += e[r] * e[r];
      angle += e[r + 1] * e[r + 1];
      along_normal += uv * uv;
    }
    radial_rms = std::sqrt(radial / static_cast<double>(n));
    angle_rms = std::sqrt(angle / static_cast<double>(n));
    out.radial_rms_mm = radial_rms;
    out.normal_rms_mm = std::sqrt(along_normal / static_cast<double>(n));
    return true;
  };
  // Exact data: weights as if the radial residual were 1e-9 of the radius and the angle 1e-9 rad.
  auto weigh = [&] {
    // Four unknowns fitted to 2n residuals: the variances corrected for the dof used.
    const double dof = std::sqrt(static_cast<double>(2 * n) / static_cast<double>(2 * n - 4));
    const double ws = 1.0 / std::max(radial_rms * dof, 1e-9 * x[3]);
    const double wn = 1.0 / std::max(angle_rms * dof, 1e-9);
    for (long r = 0; r < rows; r += 2) {
      w[r] = ws;
      w[r + 1] = wn;
    }
  };
  if (!evaluate(x)) return Status::DegenerateFit;
  for (int it = 0; it < 20; ++it) {
    weigh();
    const Eigen::MatrixXd Jw = w.asDiagonal() * J;
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> step_qr(Jw);
    if (step_qr.rank() < 4) return Status::DegenerateFit;
    const Eigen::Vector4d step = step_qr.solve(-(w.asDiagonal() * e));
    if (!step.allFinite()) return Status::DegenerateFit;
    x += step;
    if (!evaluate(x)) return Status::DegenerateFit;
    if (step.norm() < 1e-12 * x[3]) break;
  }
  // Covariance (J^T W J)^-1 with the weights of the final residuals.
  weigh();
  const Eigen::MatrixXd Jw = w.asDiagonal() * J;
  const Eigen::Matrix4d cov = (Jw.transpose() * Jw).inverse();
  out.centre_mm = mean + x.head<3>();
  out.centre_sigma_mm = cov.diagonal().head<3>().cwiseMax(0.0).cwiseSqrt();
  out.radius_mm = x[3];
  out.radius_sigma_mm = std::sqrt(std::max(0.0, cov(3, 3)));
  out.points = static_cast<int>(n);
  if (!(out.radius_mm > 0.0) || !std::isfinite(out.radius_sigma_mm) || !out.centre_sigma_mm.allFinite())
    return Status::DegenerateFit;
  return Status::Ok;
}

namespace {

// The frames with a pose of one recording.
struct Track {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> positions, normals;
};

Track collect(std::span<const PoseSample> samples) {
  Track track;
  for (const PoseSample& s : samples) {
    if (!s.valid) continue;
    track.t.push_back(s.t_s);
    track.positions.push_back(translation(s.pose));
    track.normals.push_back(rotationMatrix(s.pose).col(2));
  }
  return track;
}

// The swing's frame counts and both periods; the period of `options` becomes the
// measured one.
Status measureSwing(std::span<const PoseSample> samples, const Track& swing, const PendulumAnalysisOptions& options,
                    PendulumAnalysis& out) {
  out.frames = static_cast<int>(samples.size());
  out.valid_frames = static_cast<int>(swing.t.size());
  if (out.frames < kPendulumMinFrames) return Status::TooFewFrames;
  if (2 * out.valid_frames <= out.frames) return Status::TargetLost;
  if (out.valid_frames < kPendulumMinFrames) return Status::TooFewFrames;
  const Status s = estimatePeriod(swing.t, swing.positions, out.period);
  if (!ok(s)) return s;
  out.maxima_status = estimatePeriodByMaxima(swing.t, swing.positions, out.period.period_s, out.maxima);
  if (options.period_method == PeriodMethod::Maxima) {
    if (!ok(out.maxima_status)) return out.maxima_status;
    out.period_s = out.maxima.period_s;
    out.period_sigma_s = out.maxima.period_sigma_s;
  } else {
    out.period_s = out.period.period_s;
    out.period_sigma_s = out.period.period_sigma_s;
  }
  return Status::Ok;
}

// With the period and the sphere known: the swing angle about the pivot, its
// amplitude, the small-amplitude period and g.
Status finishAnalysis(const Track& swing, const PendulumAnalysisOptions& options, PendulumAnalysis& out) {
  const std::vector<double>& t = swing.t;
  const std::vector<Eigen::Vector3d>& positions = swing.positions;
  out.length_mm = out.sphere.radius_mm;
  out.length_sigma_mm = out.sphere.radius_sigma_mm;

  // Swing angle about the pivot, from the mean hanging direction, in the plane of the
  // swing (the hanging direction and the swing direction: the target need not lie in it).
  Eigen::Vector3d down = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : positions) down += (q - out.sphere.centre_mm).normalized();
  down.normalize();
  Eigen::Vector3d across = out.period.direction - out.period.direction.dot(down) * down;
  if (!(across.norm() > 1e-9)) return Status::DegenerateFit;
  across.normalize();
  out.swing_angle_deg.resize(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Eigen::Vector3d v = positions[i] - out.sphere.centre_mm;
    out.swing_angle_deg[i] = std::atan2(v.dot(across), v.dot(down)) / kRadPerDeg;
  }
  // Amplitude: the sinusoid of the measured period through the swing angle.
  const double omega = 2.0 * M_PI / out.period_s;
  const SineFit angle = fitSine(t, out.swing_angle_deg, omega);
  if (!angle.ok) return Status::DegenerateFit;
  const double dof = std::max(1.0, static_cast<double>(t.size()) - 3.0);
  out.amplitude_deg = angle.amplitude();
  out.amplitude_sigma_deg = std::sqrt(angle.rss / dof) * std::sqrt(2.0 / static_cast<double>(t.size()));

  // T0 = T / factor(theta0); its uncertainty from T's and theta0's.
  const double theta0 = out.amplitude_deg * kRadPerDeg;
  const double factor = options.amplitude_correction ? pendulumPeriodFactor(theta0) : 1.0;
  out.small_amplitude_period_s = out.period_s / factor;
  double sigma2 = std::pow(out.period_sigma_s / factor, 2);
  if (options.amplitude_correction) {
    const double h = 1e-4;
    const double dfactor = (pendulumPeriodFactor(theta0 + h) - pendulumPeriodFactor(std::max(0.0, theta0 - h))) /
                           (theta0 + h - std::max(0.0, theta0 - h));
    sigma2 += std::pow(out.period_s / (factor * factor) * dfactor * out.amplitude_sigma_deg * kRadPerDeg, 2);
  }
  out.small_amplitude_period_sigma_s = std::sqrt(sigma2);

  const double length_m = out.length_mm / 1000.0;
  auto g_of = [&](double period) { return 4.0 * M_PI * M_PI * length_m / (period * period); };
  out.g_m_s2 = g_of(out.small_amplitude_period_s);
  out.g_uncorrected_m_s2 = g_of(out.period_s);
  out.g_sigma_m_s2 = out.g_m_s2 * std::sqrt(std::pow(out.length_sigma_mm / out.length_mm, 2) +
                                            std::pow(2.0 * out.small_amplitude_period_sigma_s /
                                                         out.small_amplitude_period_s, 2));
  if (!std::isfinite(out.g_m_s2) || !std::isfinite(out.g_sigma_m_s2)) return Status::DegenerateFit;
  return Status::Ok;
}

}  // namespace

Status analyzePendulum(std::span<const PoseSample> samples, const PendulumAnalysisOptions& options,
                       PendulumAnalysis& out) {
  out = PendulumAnalysis{};
  const Track swing = collect(samples);
  Status s = measureSwing(samples, swing, options, out);
  if (!ok(s)) return s;
  s = fitConstrainedSphere(swing.positions, swing.normals, out.sphere);
  if (!ok(s)) return s;
  return finishAnalysis(swing, options, out);
}

Status analyzePendulumStillSwing(std::span<const PoseSample> still, std::span<const PoseSample> swing,
                                 const PendulumAnalysisOptions& options, PendulumAnalysis& out) {
  out = PendulumAnalysis{};
  const Track swing_track = collect(swing);
  Status s = measureSwing(swing, swing_track, options, out);
  if (!ok(s)) return s;
  const Track still_track = collect(still);
  out.length_from_still = true;
  out.still_frames = static_cast<int>(still.size());
  out.still_valid_frames = static_cast<int>(still_track.t.size());
  s = fitConstrainedSphere(still_track.positions, still_track.normals, out.sphere);
  if (!ok(s)) {
    out.still_failed = true;
    return s;
  }
  return finishAnalysis(swing_track, options, out);
}

}  // namespace imagepro
