#include "core/reconstruction/rim_fit.h"

#include <algorithm>
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

}  // namespace

double rimShareSeen(const Ellipse& e, const std::vector<Eigen::Vector2d>& points) {
  if (!(e.a > 0.0 && e.b > 0.0)) return 0.0;
  const double th = e.angle_deg * M_PI / 180.0;
  const double cs = std::cos(th), sn = std::sin(th);
  std::uint64_t arcs = 0;
  for (const Eigen::Vector2d& p : points) {
    const double dx = p.x() - e.cx, dy = p.y() - e.cy;
    const double t = std::atan2((-dx * sn + dy * cs) / e.b, (dx * cs + dy * sn) / e.a);
    const int arc = std::clamp(static_cast<int>((t + M_PI) / (2.0 * M_PI) * kRimArcs), 0, kRimArcs - 1);
    arcs |= std::uint64_t{1} << arc;
  }
  int held = 0;
  for (int k = 0; k < kRimArcs; ++k) held += static_cast<int>((arcs >> k) & 1U);
  return static_cast<double>(held) / kRimArcs;
}

Status fitRim(std::vector<Eigen::Vector2d>& ideal, std::vector<Eigen::Vector2d>& seen, bool robust,
              RimFitWorkspace& ws, RimFit& out) {
  out = RimFit{};
  if (const Status st = fitAll(ideal, out.fit); !ok(st)) return st;
  if (robust) {
    // Every round judges all the points against the last fit, so a point left out while an
    // occluder's edge still pulled the ellipse comes back once the fit is the rim's.
    const std::size_t n = ideal.size();
    ws.all_ideal.assign(ideal.begin(), ideal.end());
    ws.all_seen.assign(seen.begin(), seen.end());
    ws.keep.assign(n, 1);
    ws.residuals.resize(n);
    for (int round = 0; round < kMaxRounds; ++round) {
      for (std::size_t i = 0; i < n; ++i)
        ws.residuals[i] = std::abs(sampsonDistance(out.fit, ws.all_ideal[i].x(), ws.all_ideal[i].y()));
      ws.scratch.assign(ws.residuals.begin(), ws.residuals.end());
      const auto middle = ws.scratch.begin() + static_cast<std::ptrdiff_t>(n / 2);
      std::nth_element(ws.scratch.begin(), middle, ws.scratch.end());
      const double band = std::max(kMinRimBandPx, kRimSigmas * kMadToSigma * *middle);
      bool changed = false;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t keep = ws.residuals[i] <= band ? 1 : 0;
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
