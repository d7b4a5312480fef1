#include "core/reconstruction/rim_fit.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <span>

namespace imagepro {

namespace {

constexpr int kMaxRounds = 6;
constexpr double kMadToSigma = 1.4826;  // a Gaussian's sigma from its median absolute deviation

Status fitAll(const std::vector<Eigen::Vector2d>& points, EllipseFit& fit) {
  ConicMoments moments;
  moments.add(std::span<const Eigen::Vector2d>(points));
  return fitEllipse(moments, fit);
}

// The arc (0..31, each 11.25 deg of the eccentric angle) of a point at (x, y) in the frame
// where the ellipse is the unit circle: its octant by the signs and the larger coordinate,
// then a quarter of the octant by the tangents of 11.25, 22.5 and 33.75 deg (no atan).
int arcOf(double x, double y) {
  static_assert(kRimArcs == 32, "eight octants of four arcs");
  constexpr double kTan[3] = {0.19891236737965800, 0.41421356237309510, 0.66817863791929890};
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = std::max(ax, ay), lo = std::min(ax, ay);
  const int quarter = (lo > hi * kTan[0]) + (lo > hi * kTan[1]) + (lo > hi * kTan[2]);
  const int first = ax >= ay ? quarter : 7 - quarter;  // 0..7 from the x axis in this quadrant
  if (x >= 0.0) return y >= 0.0 ? first : 31 - first;
  return y >= 0.0 ? 15 - first : 16 + first;
}

}  // namespace

double rimShareSeen(const Ellipse& e, const std::vector<Eigen::Vector2d>& points) {
  if (!(e.a > 0.0 && e.b > 0.0)) return 0.0;
  const double th = e.angle_deg * M_PI / 180.0;
  const double ca = std::cos(th) / e.a, sa = std::sin(th) / e.a, cb = std::cos(th) / e.b, sb = std::sin(th) / e.b;
  std::uint32_t arcs = 0;
  for (const Eigen::Vector2d& p : points) {
    const double dx = p.x() - e.cx, dy = p.y() - e.cy;
    arcs |= std::uint32_t{1} << arcOf(dx * ca + dy * sa, dy * cb - dx * sb);
  }
  return static_cast<double>(std::popcount(arcs)) / kRimArcs;
}

Status fitRim(std::vector<Eigen::Vector2d>& ideal, std::vector<Eigen::Vector2d>& seen, bool robust,
              RimFitWorkspace& ws, RimFit& out) {
  out = RimFit{};
  if (const Status st = fitAll(ideal, out.fit); !ok(st)) return st;
  // A clean rim, every point within the least band of the plain fit, is done without a
  // median (squared distances: no root).
  const double least2 = kMinRimBandPx * kMinRimBandPx;
  const bool clean = std::all_of(ideal.begin(), ideal.end(), [&](const Eigen::Vector2d& p) {
    return squaredSampsonDistance(out.fit, p.x(), p.y()) <= least2;
  });
  if (robust && !clean) {
    // Every round judges all the points against the last fit, so a point left out while an
    // occluder's edge still pulled the ellipse comes back once the fit is the rim's.
    const std::size_t n = ideal.size();
    ws.all_ideal.assign(ideal.begin(), ideal.end());
    ws.all_seen.assign(seen.begin(), seen.end());
    ws.keep.assign(n, 1);
    ws.residuals.resize(n);
    for (int round = 0; round < kMaxRounds; ++round) {
      for (std::size_t i = 0; i < n; ++i)
        ws.residuals[i] = squaredSampsonDistance(out.fit, ws.all_ideal[i].x(), ws.all_ideal[i].y());
      ws.scratch.assign(ws.residuals.begin(), ws.residuals.end());
      const auto middle = ws.scratch.begin() + static_cast<std::ptrdiff_t>(n / 2);
      std::nth_element(ws.scratch.begin(), middle, ws.scratch.end());
      const double band = std::max(kMinRimBandPx, kRimSigmas * kMadToSigma * std::sqrt(*middle));
      bool changed = false;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t keep = ws.residuals[i] <= band * band ? 1 : 0;
        changed = changed || keep != ws.keep[i];
        ws.keep[i] = keep;
      }
      if (!changed) break;  // the same points as the last fit's: it is the rim's
      ideal.clear();
      seen.clear();
      for (std::size_t i = 0; i < n; ++i) {
        if (!ws.keep[i]) continue;
        ideal.push_back(ws.all_ideal[i]);
        if (i < ws.all_seen.size()) seen.push_back(ws.all_seen[i]);
      }
      if (ideal.size() < 6) return Status::TooFewPoints;
      if (const Status st = fitAll(ideal, out.fit); !ok(st)) return st;
    }
  }
  out.kept = ideal.size();
  out.seen = rimShareSeen(out.fit.ellipse, ideal);
  return Status::Ok;
}

}  // namespace imagepro
