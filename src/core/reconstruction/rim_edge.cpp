// The rim edge model (rim_edge.h).
#include "core/reconstruction/rim_edge.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/reconstruction/feature_geometry.h"

namespace imagepro {

using feature_detail::ceilToInt;
using feature_detail::EllipseForm;
using feature_detail::floorToInt;
using feature_detail::levelCrossing;
using feature_detail::PixelLine;
using feature_detail::roundToInt;

namespace {

constexpr double kProbeNearPx = 2.0, kProbeFarPx = 3.0;  // level probes either side of a crossing
constexpr std::size_t kMinCrossings = 8;
// The levels' planes and the blur take every k-th crossing, at most about this many: three
// parameters a side and a median need no more, and a rim has up to 160 points (320
// without the model).
constexpr std::size_t kMaxProbes = 64;
constexpr double kSharpEdgeSigmaPx = 0.8;  // below: the area estimate; above: the mid-level crossing
constexpr double kMaxMovePx = 1.5;         // a point the model would move further keeps its place
constexpr double kOutlierSigmas = 3.0;
// A crossing whose own plateaus (the probes either side) lie further than this share of
// the rim's contrast from the planes is not the paper-to-card edge: a clamp or tape lying
// over the card beside the rim (its grey for the card's black), or a glare on the paper
// beside it. Its point is left out. The planes' mid-level would place it off the rim by a
// fraction of a pixel on one arc: within the rim fit's band, yet enough to turn a target
// seen nearly along its axis to the rim's other circle (docs/reconstruction.md).
constexpr double kPlateauDisagreement = 0.35;

double medianOf(std::vector<double>& v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

PixelLine lineOf(const cv::Mat& grey, const RimCrossing& c) {
  return c.row ? PixelLine::row(grey, c.line) : PixelLine::column(grey, c.line);
}

double& along(Eigen::Vector2d& p, bool row) { return row ? p.x() : p.y(); }

// Least squares of value(row) = model . features(row) over the `rows` within
// kOutlierSigmas robust sigmas (at least `floor`) of `start`: a spot, the scene beyond the
// card or a noisy rise leaves its rows out. `start` when fewer than kMinCrossings remain
// or they do not fix the model.
template <typename Features, typename Value>
Eigen::Vector3d robustFit(FeatureWorkspace& ws, const std::vector<Eigen::Vector4d>& rows, Features features,
                          Value value, const Eigen::Vector3d& start, double floor) {
  std::vector<double>& residuals = ws.rim_residuals;
  std::vector<double>& scratch = ws.rim_scratch;
  residuals.resize(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    residuals[i] = std::abs(value(rows[i]) - start.dot(features(rows[i])));
  scratch.assign(residuals.begin(), residuals.end());
  const double limit = kOutlierSigmas * 1.4826 * std::max(floor, medianOf(scratch));
  // The normal equations' upper triangle and right-hand side, summed by hand: three
  // unknowns, a few dozen rows.
  double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (residuals[i] > limit) continue;
    const Eigen::Vector3d q = features(rows[i]);
    const double v = value(rows[i]);
    a00 += q[0] * q[0], a01 += q[0] * q[1], a02 += q[0] * q[2];
    a11 += q[1] * q[1], a12 += q[1] * q[2], a22 += q[2] * q[2];
    b0 += q[0] * v, b1 += q[1] * v, b2 += q[2] * v;
    ++kept;
  }
  if (kept < kMinCrossings) return start;
  Eigen::Matrix3d normal;
  normal << a00, a01, a02, a01, a11, a12, a02, a12, a22;
  const Eigen::LDLT<Eigen::Matrix3d> solver(normal);
  if (solver.info() != Eigen::Success || !solver.isPositive()) return start;
  const Eigen::Vector3d model = solver.solve(Eigen::Vector3d(b0, b1, b2));
  return model.allFinite() ? model : start;
}

// The plane of the probes' column k (2 dark, 3 bright) over their position (0, 1), from
// the median; its residuals' spread counted at least a grey level (a clean edge's probes
// agree to the integer).
Eigen::Vector3d robustPlane(FeatureWorkspace& ws, int k) {
  std::vector<double>& scratch = ws.rim_scratch;
  scratch.clear();
  for (const Eigen::Vector4d& p : ws.rim_probes) scratch.push_back(p[k]);
  const double median = medianOf(scratch);
  return robustFit(
      ws, ws.rim_probes, [](const Eigen::Vector4d& p) { return Eigen::Vector3d(1.0, p[0], p[1]); },
      [k](const Eigen::Vector4d& p) { return p[k]; }, Eigen::Vector3d(median, 0.0, 0.0), 1.0);
}

}  // namespace

RimEdgeFit modelRimEdge(const cv::Mat& grey, const Ellipse& detected, FeatureWorkspace& ws,
                        std::vector<Eigen::Vector2d>& points) {
  RimEdgeFit fit;
  const std::vector<RimCrossing>& crossings = ws.rim_crossings;
  if (crossings.size() != points.size() || crossings.size() < kMinCrossings) return fit;
  const EllipseForm form(detected, 1.0);
  const Eigen::Vector2d centre(form.cx, form.cy);

  // The detected ellipse's gradient at a point, (g_x, g_y) = (P dx + Q dy, Q dx + R dy): the
  // rim's outward normal is g / |g|, its radius of curvature |g|^3 / |t' H t| with the
  // tangent t = (-g_y, g_x).
  auto gradientAt = [&](const Eigen::Vector2d& p) {
    const double dx = p.x() - form.cx, dy = p.y() - form.cy;
    return Eigen::Vector2d(form.P * dx + form.Q * dy, form.Q * dx + form.R * dy);
  };

  // 1. The levels: probes on both sides of the crossings, a plane through each side's.
  // Odd, so that a row's two crossings (stored side by side) are both sampled.
  const std::size_t stride = (points.size() + kMaxProbes - 1) / kMaxProbes | 1;
  ws.rim_probes.clear();
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const RimCrossing& c = crossings[i];
    const PixelLine line = lineOf(grey, c);
    const double at = c.row ? points[i].x() : points[i].y();
    double o1, o2, i1, i2;
    if (!line.interp(at - c.inwards * kProbeNearPx, o1) || !line.interp(at - c.inwards * kProbeFarPx, o2) ||
        !line.interp(at + c.inwards * kProbeNearPx, i1) || !line.interp(at + c.inwards * kProbeFarPx, i2))
      continue;
    const Eigen::Vector2d d = points[i] - centre;
    ws.rim_probes.emplace_back(d.x(), d.y(), 0.5 * (o1 + o2), 0.5 * (i1 + i2));
  }
  if (ws.rim_probes.size() < kMinCrossings) return fit;
  const Eigen::Vector3d darkPlane = robustPlane(ws, 2), brightPlane = robustPlane(ws, 3);
  auto levelsAt = [&](const Eigen::Vector2d& p, double& dark, double& contrast) {
    const Eigen::Vector3d q(1.0, p.x() - centre.x(), p.y() - centre.y());
    dark = darkPlane.dot(q);
    contrast = brightPlane.dot(q) - dark;
    return contrast > 0.0;
  };

  // 2. The blur, as a covariance (motion blur spreads along one direction): across a
  // Gaussian-blurred step of contrast C the profile rises at most C / (s sqrt(2 pi)) per
  // pixel, s the blur's spread along the edge's normal n, s^2 = n' S n; read along a row or
  // column at cosine c to n the rise is c times that. Each sampled crossing gives s^2 from the rise between
  // the two pixels that straddle it; S is fitted to them.
  std::vector<Eigen::Vector4d>& spreads = ws.rim_probes;  // n_x^2, 2 n_x n_y, n_y^2, s^2
  spreads.clear();
  // About half as many crossings as the levels took: S has three parameters and no sides.
  for (std::size_t i = 0; i < points.size(); i += 2 * stride + 1) {
    const RimCrossing& c = crossings[i];
    const PixelLine line = lineOf(grey, c);
    const int k = floorToInt(c.row ? points[i].x() : points[i].y());
    const Eigen::Vector2d n = gradientAt(points[i]).normalized();
    double dark, contrast;
    if (!line.contains(k) || !line.contains(k + 1) || !levelsAt(points[i], dark, contrast)) continue;
    const double rise = std::abs(line.at(k + 1) - line.at(k));
    const double cosine = std::abs(c.row ? n.x() : n.y());
    if (!(rise > 0.0)) continue;
    const double spread = contrast * cosine / (rise * std::sqrt(2.0 * M_PI));
    spreads.emplace_back(n.x() * n.x(), 2.0 * n.x() * n.y(), n.y() * n.y(), spread * spread);
  }
  if (spreads.size() < kMinCrossings) return fit;
  std::vector<double>& scratch = ws.rim_scratch;
  scratch.clear();
  for (const Eigen::Vector4d& r : spreads) scratch.push_back(r[3]);
  const double isotropic = medianOf(scratch);
  const Eigen::Vector3d sxy = robustFit(
      ws, spreads, [](const Eigen::Vector4d& r) { return Eigen::Vector3d(r[0], r[1], r[2]); },
      [](const Eigen::Vector4d& r) { return r[3]; }, Eigen::Vector3d(isotropic, 0.0, isotropic), 0.01);
  // S, its eigenvalues kept from going negative on a noisy fit.
  Eigen::Matrix2d blur;
  blur << sxy[0], sxy[1], sxy[1], sxy[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(blur);
  blur = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * eigen.eigenvectors().transpose();
  const double sigma = std::sqrt(0.5 * blur.trace());

  // 3. Every point again on its line, with the levels where it lies: by the area under the
  // profile where the edge is sharp across (s below 0.8 px), else at the mid-level.
  // 4. Then out by the blur's shrink of a curved edge, t' S t / (2 rho) with t the rim's
  // tangent (the spread along the edge is what carries light round the curve), along the
  // point's own line; a point the model could not place again is moved all the same.
  auto placePoint = [&](std::size_t i, const RimCrossing& c, const PixelLine& line, bool levels, double dark,
                        double contrast) {
    // In terms of the gradient g (no square root per point): the spread across the edge is
    // g' S g / |g|^2, along it t' S t / |g|^2, the line's cosine to the normal g_line / |g|.
    const Eigen::Vector2d g = gradientAt(points[i]);
    const double g2 = g.squaredNorm(), gLine = c.row ? g.x() : g.y();
    if (!(g2 > 0.0)) return;
    const Eigen::Vector2d t(-g.y(), g.x());
    double& coordinate = along(points[i], c.row);
    if (levels) {
      const double across2 = g.dot(blur * g) / g2;
      double at = coordinate;
      bool found = true;
      if (across2 < kSharpEdgeSigmaPx * kSharpEdgeSigmaPx) {
        // The white run's length within +-2.5 s along the line, the window re-centred once or twice.
        const double cosine = std::max(std::abs(gLine) / std::sqrt(g2), 0.5);
        const int halfWindow = std::max(1, ceilToInt(2.5 * std::sqrt(across2) / cosine));
        for (int pass = 0; pass < 3; ++pass) {
          const int mid = roundToInt(at);
          if (!line.contains(mid - halfWindow) || !line.contains(mid + halfWindow)) {
            found = false;
            break;
          }
          double sum = 0.0;
          for (int j = -halfWindow; j <= halfWindow; ++j) sum += line.at(mid + j);
          const double white = (sum - (2 * halfWindow + 1) * dark) / contrast;
          at = mid + c.inwards * (halfWindow + 0.5 - white);
          if (roundToInt(at) == mid) break;
        }
      } else {
        // Mostly the two pixels either side of the point straddle the level already.
        const double level = dark + 0.5 * contrast;
        const int k = floorToInt(at);
        const double g0 = line.contains(k) ? line.at(k) : -1.0, g1 = line.contains(k + 1) ? line.at(k + 1) : -1.0;
        if (g0 >= 0.0 && g1 >= 0.0 && (g1 - g0) * c.inwards > 0.0 && (g0 - level) * (g1 - level) <= 0.0)
          at = k + (level - g0) / (g1 - g0);
        else
          found = levelCrossing(line, c.inwards, level, at);
      }
      if (found && std::abs(at - coordinate) <= kMaxMovePx) {
        coordinate = at;
        ++fit.moved;
      }
    }
    // Rows are taken where the rim's normal is within 45 deg of them, columns likewise:
    // the shift (t' S t / |g|^2) / (2 rho) along the normal is that over the cosine along
    // the line, with rho = |g|^3 / |t' H t|.
    if (gLine * gLine >= 0.25 * g2) {
      const double tHt = std::abs(form.P * t.x() * t.x() + 2.0 * form.Q * t.x() * t.y() + form.R * t.y() * t.y());
      coordinate += 0.5 * t.dot(blur * t) * tHt / (g2 * g2 * gLine);
    }
  };
  // First, a crossing whose own plateaus (the probes either side) stray from the planes is
  // left out (kPlateauDisagreement): the rest are kept in order.
  const double plateauLimit = kPlateauDisagreement * (brightPlane[0] - darkPlane[0]);
  std::vector<RimCrossing>& kept = ws.rim_crossings;
  std::size_t n = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const RimCrossing c = crossings[i];  // a copy: kept[n] below may be this very entry
    double dark = 0.0, contrast = 0.0;
    const bool levels = levelsAt(points[i], dark, contrast);
    const PixelLine line = lineOf(grey, c);
    if (levels) {
      const double at = c.row ? points[i].x() : points[i].y();
      double o1, o2, i1, i2;
      if (line.interp(at - c.inwards * kProbeNearPx, o1) && line.interp(at - c.inwards * kProbeFarPx, o2) &&
          line.interp(at + c.inwards * kProbeNearPx, i1) && line.interp(at + c.inwards * kProbeFarPx, i2) &&
          (std::abs(0.5 * (o1 + o2) - dark) > plateauLimit ||
           std::abs(0.5 * (i1 + i2) - dark - contrast) > plateauLimit)) {
        ++fit.left_out;
        continue;
      }
    }
    placePoint(i, c, line, levels, dark, contrast);
    points[n] = points[i];
    kept[n] = c;
    ++n;
  }
  points.resize(n);
  kept.resize(n);

  fit.fitted = true;
  fit.dark = darkPlane[0];
  fit.bright = brightPlane[0];
  fit.blur_covariance = blur;
  fit.blur_sigma_px = sigma;
  return fit;
}

}  // namespace imagepro
