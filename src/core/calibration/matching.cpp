#include "core/calibration/matching.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/reconstruction/pose.h"

namespace imagepro {
namespace {

constexpr double kCellPx = 16.0;
// How far outside the image an ideal position may lie: the polynomial of eq. 4.7 folds far
// outside (at a few image widths it can put a point back into the image).
constexpr double kOutsideMarginFraction = 0.1;

// Area of the ellipse x^T M x = 0 (x = (u, v, 1)); 0 when it is not a real ellipse.
double conicArea(const Eigen::Matrix3d& M, const Eigen::Vector2d& centre) {
  const Eigen::Matrix2d A = M.topLeftCorner<2, 2>();
  const double det = A.determinant();
  if (!(det > 0.0)) return 0.0;
  const Eigen::Vector3d c(centre.x(), centre.y(), 1.0);
  const double valueAtCentre = c.dot(M * c);
  if (!(valueAtCentre * A(0, 0) < 0.0)) return 0.0;
  return M_PI * std::abs(valueAtCentre) / std::sqrt(det);
}

struct BucketGrid {
  int nx = 0, ny = 0;
  int cellX(double u) const { return std::clamp(static_cast<int>(std::floor(u / kCellPx)), 0, nx - 1); }
  int cellY(double v) const { return std::clamp(static_cast<int>(std::floor(v / kCellPx)), 0, ny - 1); }
};

BucketGrid buildGrid(const CameraModel& camera, std::span<const ObservedSpot> observed, MatchWorkspace& ws) {
  BucketGrid g;
  g.nx = std::max(1, static_cast<int>(std::ceil(camera.width / kCellPx)));
  g.ny = std::max(1, static_cast<int>(std::ceil(camera.height / kCellPx)));
  ws.cellStart.assign(static_cast<size_t>(g.nx * g.ny + 1), 0);
  for (const ObservedSpot& o : observed) ++ws.cellStart[g.cellY(o.centre.y()) * g.nx + g.cellX(o.centre.x()) + 1];
  std::partial_sum(ws.cellStart.begin(), ws.cellStart.end(), ws.cellStart.begin());
  ws.cellItems.resize(observed.size());
  ws.cellFill.assign(ws.cellStart.begin(), ws.cellStart.end() - 1);
  for (int k = 0; k < static_cast<int>(observed.size()); ++k) {
    const int cell = g.cellY(observed[k].centre.y()) * g.nx + g.cellX(observed[k].centre.x());
    ws.cellItems[ws.cellFill[cell]++] = k;
  }
  return g;
}

}  // namespace

void projectPatternSpots(const CameraModel& camera, const PatternGeometry& pattern,
                         std::span<const PatternSpot> spots, const Pose& pose, std::vector<IdealSpot>& out) {
  out.clear();
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  const double radius = patternSpotRadiusMm(pattern);
  const double s = pattern.spot_spacing_mm;
  auto project = [&](const Eigen::Vector2d& p, Eigen::Vector2d& uv) {
    const Eigen::Vector3d P = R * Eigen::Vector3d(p.x(), p.y(), 0.0) + T;
    if (!(P.z() > 0.0)) return false;
    uv = projectIdeal(camera, P);
    return true;
  };
  auto inside = [&](const Eigen::Vector2d& p, double margin) {
    return p.x() >= -0.5 - margin && p.y() >= -0.5 - margin && p.x() <= camera.width - 0.5 + margin &&
           p.y() <= camera.height - 0.5 + margin;
  };
  // Every point of the spot must lie in front of the camera for its image to be an ellipse.
  const double minDepth = radius * R.col(2).head<2>().norm() + 1e-6;
  for (int k = 0; k < static_cast<int>(spots.size()); ++k) {
    const PatternSpot& spot = spots[k];
    const Eigen::Vector3d P = R * Eigen::Vector3d(spot.position_mm.x(), spot.position_mm.y(), 0.0) + T;
    if (!(P.z() > minDepth)) continue;
    const Eigen::Matrix3d M =
        imageConicOfTargetCircle(camera, pose, spot.position_mm.x(), spot.position_mm.y(), radius);
    Eigen::Vector2d centre;
    if (!conicMatrixCentre(M, centre)) continue;
    if (!inside(centre, kOutsideMarginFraction * std::hypot(camera.width, camera.height)) ||
        !inside(distortPixel(camera, centre), 0.0))
      continue;
    const double area = conicArea(M, centre);
    if (!(area > 0.0)) continue;
    double spacing = std::numeric_limits<double>::infinity();
    const Eigen::Vector2d steps[4] = {{s, 0.0}, {-s, 0.0}, {0.0, s}, {0.0, -s}};
    const Eigen::Vector2d centreIdeal = projectIdeal(camera, P);
    for (const Eigen::Vector2d& d : steps) {
      Eigen::Vector2d uv;
      if (project(spot.position_mm + d, uv)) spacing = std::min(spacing, (uv - centreIdeal).norm());
    }
    if (!std::isfinite(spacing)) continue;
    out.push_back({k, spot.column, spot.row, centre, area, spacing});
  }
}

void matchSpots(const CameraModel& camera, const PatternGeometry& pattern, std::span<const IdealSpot> ideal,
                std::span<const ObservedSpot> observed, bool neighbourPrediction, MatchWorkspace& ws,
                std::vector<SpotMatch>& matches, MatchStats& stats) {
  matches.clear();
  stats = {};
  const BucketGrid grid = buildGrid(camera, observed, ws);
  ws.claimedBy.assign(observed.size(), -1);

  const int columns = std::max(pattern.columns, 1);
  const int rows = std::max(pattern.rows, 1);
  ws.nodeMatch.assign(static_cast<size_t>(columns) * rows, -1);
  ws.nodeResidual.resize(ws.nodeMatch.size());

  const Eigen::Vector2d pp(camera.u0(), camera.v0());
  ws.order.resize(ideal.size());
  std::iota(ws.order.begin(), ws.order.end(), 0);
  std::sort(ws.order.begin(), ws.order.end(), [&](int a, int b) {
    return (ideal[a].ideal - pp).squaredNorm() < (ideal[b].ideal - pp).squaredNorm();
  });

  auto neighbourResidual = [&](const IdealSpot& s, int reach, Eigen::Vector2d& mean) {
    mean.setZero();
    int n = 0;
    for (int dr = -reach; dr <= reach; ++dr)
      for (int dc = -reach; dc <= reach; ++dc) {
        const int c = s.column + dc, r = s.row + dr;
        if (c < 0 || r < 0 || c >= columns || r >= rows) continue;
        const size_t node = static_cast<size_t>(r) * columns + c;
        if (ws.nodeMatch[node] < 0) continue;
        mean += ws.nodeResidual[node];
        ++n;
      }
    if (n > 0) mean /= n;
    return n > 0;
  };

  for (const int i : ws.order) {
    const IdealSpot& s = ideal[i];
    const Eigen::Vector2d modelled = distortPixel(camera, s.ideal);
    Eigen::Vector2d residual = Eigen::Vector2d::Zero();
    if (neighbourPrediction && !neighbourResidual(s, 1, residual)) neighbourResidual(s, 2, residual);
    const Eigen::Vector2d predicted = modelled + residual;
    const double gate = 0.5 * s.spacing_px;

    int best = -1;
    bool second = false;
    double d1 = std::numeric_limits<double>::infinity();
    const int cx0 = grid.cellX(predicted.x() - gate), cx1 = grid.cellX(predicted.x() + gate);
    const int cy0 = grid.cellY(predicted.y() - gate), cy1 = grid.cellY(predicted.y() + gate);
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx) {
        const int cell = cy * grid.nx + cx;
        for (int e = ws.cellStart[cell]; e < ws.cellStart[cell + 1]; ++e) {
          const int k = ws.cellItems[e];
          const double d = (observed[k].centre - predicted).norm();
          if (d > gate) continue;
          const double area = observed[k].area_px;
          if (area * kAreaTolerance < s.area_px || area > kAreaTolerance * s.area_px) continue;
          if (best >= 0) second = true;
          if (d < d1) {
            d1 = d;
            best = k;
          }
        }
      }
    if (best < 0) {
      ++stats.missing;
      continue;
    }
    if (second || ws.claimedBy[best] >= 0) {
      ++stats.ambiguous;
      continue;
    }
    ws.claimedBy[best] = i;
    const size_t node = static_cast<size_t>(s.row) * columns + s.column;
    ws.nodeMatch[node] = best;
    ws.nodeResidual[node] = observed[best].centre - modelled;
    matches.push_back({i, best, d1, gate});
    ++stats.matched;
  }
}

}  // namespace imagepro
