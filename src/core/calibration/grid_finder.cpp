#include "core/calibration/grid_finder.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <utility>

#include "core/calibration/spots.h"

namespace imagepro {
namespace {

constexpr double kFlatWhite = 230.0;
// A dot may cover up to this fraction of the image (a small grid close up: 4 x 5 dots of
// 20 mm filling a 640x480 image are about 55 px across, 0.8 %).
constexpr double kMaxDotAreaFraction = 0.04;
// A lattice step may differ from the one before by this fraction of the shorter step.
constexpr double kStepTolerance = 0.3;

struct Candidate {
  Eigen::Vector2d p;
  int area = 0;
};

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Indices of the k nearest other candidates of candidate i, nearest first.
std::vector<int> nearest(const std::vector<Candidate>& c, int i, int k) {
  std::vector<std::pair<double, int>> d;
  d.reserve(c.size());
  for (int j = 0; j < static_cast<int>(c.size()); ++j)
    if (j != i) d.emplace_back((c[j].p - c[i].p).squaredNorm(), j);
  const int n = std::min<int>(k, static_cast<int>(d.size()));
  std::partial_sort(d.begin(), d.begin() + n, d.end());
  std::vector<int> out(n);
  for (int j = 0; j < n; ++j) out[j] = d[j].second;
  return out;
}

// A seed whose four nearest neighbours lie at +-a and +-b, a and b far from parallel.
bool seedBasis(const std::vector<Candidate>& c, int i, Eigen::Vector2d& a, Eigen::Vector2d& b) {
  const std::vector<int> nb = nearest(c, i, 4);
  if (nb.size() < 4) return false;
  a = c[nb[0]].p - c[i].p;
  int opposite = -1, second = -1;
  for (int k = 1; k < 4; ++k) {
    const Eigen::Vector2d v = c[nb[k]].p - c[i].p;
    if ((v + a).norm() < kStepTolerance * a.norm()) opposite = k;
    else if (second < 0 && std::abs(cross2(a, v)) > 0.7 * a.norm() * v.norm()) second = k;
  }
  if (opposite < 0 || second < 0) return false;
  b = c[nb[second]].p - c[i].p;
  for (int k = 1; k < 4; ++k)
    if (k != opposite && k != second && (c[nb[k]].p - c[i].p + b).norm() < kStepTolerance * b.norm()) return true;
  return false;
}

using Node = std::pair<int, int>;  // (column, row) on the lattice

// The lattice grown from the candidates: each named candidate's index by node.
std::map<Node, int> growLattice(const std::vector<Candidate>& c) {
  std::map<Node, int> best;
  if (c.size() < 5) return best;
  // Seeds from the middle of the candidates out (a partial view's middle is most regular).
  Eigen::Vector2d mid = Eigen::Vector2d::Zero();
  for (const Candidate& x : c) mid += x.p;
  mid /= static_cast<double>(c.size());
  std::vector<int> order(c.size());
  for (size_t i = 0; i < c.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(),
            [&](int x, int y) { return (c[x].p - mid).squaredNorm() < (c[y].p - mid).squaredNorm(); });
  int tries = 0;
  for (const int seed : order) {
    Eigen::Vector2d a, b;
    if (!seedBasis(c, seed, a, b)) continue;
    if (cross2(a, b) < 0) std::swap(a, b);  // the lattice turns as the image does (y down)
    std::map<Node, int> named;
    std::vector<char> used(c.size(), 0);
    std::map<Node, std::pair<Eigen::Vector2d, Eigen::Vector2d>> basis;
    std::deque<Node> queue;
    named[{0, 0}] = seed;
    used[seed] = 1;
    basis[{0, 0}] = {a, b};
    queue.push_back({0, 0});
    while (!queue.empty()) {
      const Node n = queue.front();
      queue.pop_front();
      const Eigen::Vector2d p = c[named[n]].p;
      const auto [na, nb] = basis[n];
      const Node steps[4] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (const Node& s : steps) {
        const Node m{n.first + s.first, n.second + s.second};
        if (named.count(m)) continue;
        // The step predicted: the last one along this line where it is known.
        const Node back{n.first - s.first, n.second - s.second};
        Eigen::Vector2d step = s.first != 0 ? na * s.first : nb * s.second;
        if (const auto it = named.find(back); it != named.end()) step = p - c[it->second].p;
        const Eigen::Vector2d predicted = p + step;
        const double tol = kStepTolerance * std::min(na.norm(), nb.norm());
        int hit = -1;
        double d1 = 1e300, d2 = 1e300;
        for (int j = 0; j < static_cast<int>(c.size()); ++j) {
          const double d = (c[j].p - predicted).norm();
          if (d < d1) {
            d2 = d1;
            d1 = d;
            hit = j;
          } else if (d < d2) {
            d2 = d;
          }
        }
        if (hit < 0 || used[hit] || d1 > tol || d2 < 2.0 * d1) continue;
        named[m] = hit;
        used[hit] = 1;
        const Eigen::Vector2d found = c[hit].p - p;
        basis[m] = s.first != 0 ? std::make_pair(Eigen::Vector2d(found * s.first), nb)
                                : std::make_pair(na, Eigen::Vector2d(found * s.second));
        queue.push_back(m);
      }
    }
    if (named.size() > best.size()) best = std::move(named);
    // A seed that names most candidates is the grid; a few more seeds guard against a
    // seed on clutter.
    if (2 * best.size() >= c.size() || ++tries >= 5) break;
  }
  return best;
}

// Drops named dots whose area is far from their named neighbours' median (the target's
// spots on the thesis pattern, blemishes next to a dot).
void dropOddSizes(const std::vector<Candidate>& c, std::map<Node, int>& named) {
  std::vector<Node> drop;
  for (const auto& [n, i] : named) {
    std::vector<int> areas;
    for (int dr = -2; dr <= 2; ++dr)
      for (int dc = -2; dc <= 2; ++dc)
        if ((dr || dc))
          if (const auto it = named.find({n.first + dc, n.second + dr}); it != named.end())
            areas.push_back(c[it->second].area);
    if (areas.size() < 3) continue;
    std::nth_element(areas.begin(), areas.begin() + areas.size() / 2, areas.end());
    const double median = areas[areas.size() / 2];
    if (c[i].area > 1.8 * median || c[i].area < 0.5 * median) drop.push_back(n);
  }
  for (const Node& n : drop) named.erase(n);
}

// The candidates whose area is at least a quarter of the n-th largest (n: the grid's dots;
// a dot's image area varies across a tilted grid by less than that).
std::vector<Candidate> largeCandidates(const std::vector<Candidate>& c, int n) {
  if (static_cast<int>(c.size()) <= n) return c;
  std::vector<int> areas;
  for (const Candidate& x : c) areas.push_back(x.area);
  std::nth_element(areas.begin(), areas.begin() + (n - 1), areas.end(), std::greater<>());
  const double floor = 0.25 * areas[n - 1];
  std::vector<Candidate> out;
  for (const Candidate& x : c)
    if (x.area >= floor) out.push_back(x);
  return out;
}

// OpenCV's ordering of the whole grid, from the candidates' centres.
bool openCvGrid(const std::vector<Candidate>& c, const DotGridSpec& spec, std::vector<int>& order) {
  std::vector<cv::Point2f> pts;
  pts.reserve(c.size());
  for (const Candidate& x : c) pts.emplace_back(static_cast<float>(x.p.x()), static_cast<float>(x.p.y()));
  const int kindFlag =
      spec.kind == DotGridKind::AsymmetricCircles ? cv::CALIB_CB_ASYMMETRIC_GRID : cv::CALIB_CB_SYMMETRIC_GRID;
  const cv::Size size(spec.columns, spec.rows);
  std::vector<cv::Point2f> centres;
  bool found = false;
  for (const int extra : {0, static_cast<int>(cv::CALIB_CB_CLUSTERING)}) {
    try {
      found = cv::findCirclesGrid(pts, size, centres, kindFlag | extra, cv::Ptr<cv::FeatureDetector>());
    } catch (const cv::Exception&) {
      found = false;
    }
    if (found && static_cast<int>(centres.size()) == spec.columns * spec.rows) break;
    found = false;
  }
  if (!found) return false;
  order.assign(centres.size(), -1);
  for (size_t k = 0; k < centres.size(); ++k) {
    double bestD = 1e300;
    for (size_t j = 0; j < c.size(); ++j) {
      const double d = std::hypot(c[j].p.x() - centres[k].x, c[j].p.y() - centres[k].y);
      if (d < bestD) {
        bestD = d;
        order[k] = static_cast<int>(j);
      }
    }
    if (bestD > 1e-3) return false;
  }
  return true;
}

// Names a grown lattice as the whole OpenCV grid. The lattice's two steps may be any basis
// of the grid's lattice (under strong perspective the nearest neighbours of an asymmetric
// grid's dot are no longer its diagonal ones), so every basis of short steps with the
// lattice's orientation is tried, and the one that puts every dot on the grid, once, names it.
bool nameWholeGrid(const std::vector<Candidate>& c, const DotGridSpec& spec, const std::map<Node, int>& named,
                   std::vector<FoundDot>& out) {
  if (static_cast<int>(named.size()) != spec.columns * spec.rows) return false;
  const bool asym = spec.kind == DotGridKind::AsymmetricCircles;
  // Grid coordinates in spacings: symmetric (j, i), asymmetric (2 j + i mod 2, i).
  const int det = asym ? 2 : 1;
  const Node steps[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}, {2, 0}, {-2, 0}, {0, 2}, {0, -2}};
  for (const Node& A : steps)
    for (const Node& B : steps) {
      if (A.first * B.second - A.second * B.first != det) continue;
      if (asym && ((A.first + A.second) % 2 != 0 || (B.first + B.second) % 2 != 0)) continue;
      std::vector<std::pair<Node, int>> xy;
      int minY = 1 << 30;
      for (const auto& [n, i] : named) {
        const Node g{n.first * A.first + n.second * B.first, n.first * A.second + n.second * B.second};
        xy.push_back({g, i});
        minY = std::min(minY, g.second);
      }
      int minX = 1 << 30;
      for (const auto& [g, i] : xy)
        if (g.second == minY) minX = std::min(minX, g.first);
      std::vector<int> slot(static_cast<size_t>(spec.columns * spec.rows), -1);
      bool fits = true;
      for (const auto& [g, i] : xy) {
        const int X = g.first - minX, Y = g.second - minY;
        const int offset = asym ? Y % 2 : 0;
        const int stride = asym ? 2 : 1;
        if (Y >= spec.rows || X < offset || (X - offset) % stride != 0 || (X - offset) / stride >= spec.columns) {
          fits = false;
          break;
        }
        int& k = slot[static_cast<size_t>(Y * spec.columns + (X - offset) / stride)];
        if (k >= 0) {
          fits = false;
          break;
        }
        k = i;
      }
      if (!fits) continue;
      out.clear();
      for (int k = 0; k < spec.columns * spec.rows; ++k) {
        FoundDot d;
        d.column = k % spec.columns;
        d.row = k / spec.columns;
        d.object_mm = dotGridPointMm(spec, d.column, d.row);
        d.image_px = c[slot[k]].p;
        d.area_px = c[slot[k]].area;
        out.push_back(d);
      }
      return true;
    }
  return false;
}

void dotsFromLattice(const std::vector<Candidate>& c, const DotGridSpec& spec, const std::map<Node, int>& named,
                     std::vector<FoundDot>& out) {
  out.clear();
  for (const auto& [n, i] : named) {
    FoundDot d;
    d.column = n.first;
    d.row = n.second;
    d.object_mm = Eigen::Vector2d(n.first * spec.spacing_mm, n.second * spec.spacing_mm);
    d.image_px = c[i].p;
    d.area_px = c[i].area;
    out.push_back(d);
  }
}

}  // namespace

cv::Mat flattenIllumination(const cv::Mat& grey) {
  // Wider than any dot the finder takes (kMaxDotAreaFraction: a quarter of the image's
  // height across at most).
  const int k = std::max(15, std::min(grey.cols, grey.rows) / 4) | 1;
  cv::Mat white;
  cv::morphologyEx(grey, white, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  cv::blur(white, white, cv::Size(k, k));
  cv::Mat greyF, whiteF;
  grey.convertTo(greyF, CV_32F);
  white.convertTo(whiteF, CV_32F);
  // Dark surroundings (a table beyond the sheet) are not made white by their own level.
  double maxWhite = 0;
  cv::minMaxLoc(whiteF, nullptr, &maxWhite);
  whiteF = cv::max(whiteF, std::max(1.0, 0.15 * maxWhite));
  cv::Mat flat;
  cv::Mat(greyF / whiteF * kFlatWhite).convertTo(flat, CV_8U);
  return flat;
}

Status findDotGrid(const cv::Mat& grey, const DotGridSpec& spec, GridDetection& out) {
  out = {};
  if (grey.empty() || grey.type() != CV_8UC1) return out.status = Status::EmptyFrame;
  if (!dotGridSpecError(spec).empty()) return out.status = Status::InvalidPattern;
  const cv::Mat flat = flattenIllumination(grey);
  SpotFinderWorkspace ws;
  std::vector<ObservedSpot> spots;
  // White is kFlatWhite everywhere now: a fixed threshold at 0.6 of it (an automatic one
  // splits the white itself where the sheet's edge leaves it brighter).
  const Status s = findPatternSpots(
      flat, grey, ThresholdOptions{ThresholdMethod::Manual, static_cast<int>(0.6 * kFlatWhite)}, ws, spots,
      kMaxDotAreaFraction);
  if (!ok(s)) return out.status = Status::GridNotFound;
  std::vector<Candidate> c;
  c.reserve(spots.size());
  for (const ObservedSpot& o : spots) c.push_back({o.centre, o.area_px});
  out.candidates = static_cast<int>(c.size());

  if (spec.kind != DotGridKind::Thesis) {
    std::vector<int> order;
    // Small dark specks (print, text, dirt) confuse OpenCV's ordering: first only the
    // candidates near the size of the grid's smallest dot, then all.
    const std::vector<Candidate> large = largeCandidates(c, spec.columns * spec.rows);
    std::vector<int> largeOrder;
    if (large.size() < c.size() && openCvGrid(large, spec, largeOrder)) {
      c = large;
      order = largeOrder;
    }
    if (!order.empty() || openCvGrid(c, spec, order)) {
      for (size_t k = 0; k < order.size(); ++k) {
        FoundDot d;
        d.column = static_cast<int>(k) % spec.columns;
        d.row = static_cast<int>(k) / spec.columns;
        d.object_mm = dotGridPointMm(spec, d.column, d.row);
        d.image_px = c[order[k]].p;
        d.area_px = c[order[k]].area;
        out.dots.push_back(d);
      }
      return out.status = Status::Ok;
    }
    // A grid OpenCV cannot order (strong perspective, clutter): the lattice, accepted only
    // when it is the whole grid.
    std::vector<FoundDot> dots;
    const auto lattice = [](const std::vector<Candidate>& from) {
      std::map<Node, int> named = growLattice(from);
      dropOddSizes(from, named);
      return named;
    };
    if (!nameWholeGrid(large, spec, lattice(large), dots) && !nameWholeGrid(c, spec, lattice(c), dots)) return out.status = Status::GridNotFound;
    out.dots = std::move(dots);
    return out.status = Status::Ok;
  }

  std::map<Node, int> named = growLattice(c);
  dropOddSizes(c, named);
  if (static_cast<int>(named.size()) < kMinPartialGridDots) return out.status = Status::GridNotFound;
  // Not all on one line or two: a plane needs rows and columns.
  std::map<int, int> cols, rows;
  for (const auto& [n, i] : named) ++cols[n.first], ++rows[n.second];
  if (cols.size() < 3 || rows.size() < 3) return out.status = Status::GridNotFound;
  dotsFromLattice(c, spec, named, out.dots);
  out.partial = static_cast<int>(named.size()) < spec.columns * spec.rows;
  return out.status = Status::Ok;
}

}  // namespace imagepro
