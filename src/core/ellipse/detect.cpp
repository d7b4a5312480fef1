#include "core/ellipse/detect.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>

#include "core/ellipse/fast_atan2.h"
#include "core/ellipse/pixel_passes.h"

namespace imagepro {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The quick screen of the Sampson rule: Taubin's RMS distance runs close to the mean
// Sampson distance for the paths that pass (library: within a factor 1.5), so a path
// three times above the limit needs no per-point pass.
constexpr double kTaubinScreen = 3.0;
// A closed path shorter than this cannot outline a spot.
constexpr std::size_t kMinSpotPixels = 4;
// A spot's path (the white pixels around it) has an RMS radius within this factor of
// the spot's expected radius r0 / R * sqrt(a b).
constexpr double kSpotSizeFactor = 2.5;
// The two spots' paths are of one size within this factor (mayBeOccludedTarget says why).
constexpr double kSpotPairSizeRatio = 1.3;
// Dark paths of spot size a target's disk may hold, its spots among them, and by how much
// the best pair of them must sit better than the next (findSpots).
constexpr std::size_t kMaxDiskBlobs = 4;
constexpr double kClearlyBestPair = 1.0;
// The consensus fit scores its candidates on at most this many pixels of the path.
constexpr std::size_t kConsensusScorePoints = 128;

void summarise(std::span<const EdgePixel> path, PathSummary& s) {
  // Exact integer sums about the first pixel (no cancellation) and the bounding box, in
  // one pass (pixel_passes.h).
  const int ox = path[0].x, oy = path[0].y;
  const pixel_passes::PathSums sums = pixel_passes::pathSums(path, ox, oy);
  const pixel_passes::Bounds& b = sums.bounds;
  const double sx = static_cast<double>(sums.x), sy = static_cast<double>(sums.y);
  const double sxx_yy = static_cast<double>(sums.xx_yy);
  const double sgx = static_cast<double>(sums.gx), sgy = static_cast<double>(sums.gy);
  const double sgp = static_cast<double>(sums.g_dot);
  const double n = static_cast<double>(path.size());
  const double mx = sx / n, my = sy / n;
  s.bbox = cv::Rect(b.min_x, b.min_y, b.max_x - b.min_x + 1, b.max_y - b.min_y + 1);
  s.cx = ox + mx;
  s.cy = oy + my;
  s.rms_radius = std::sqrt(std::max(0.0, sxx_yy / n - mx * mx - my * my));
  s.polarity = sgp - mx * sgx - my * sgy;  // sum of g . (p - centroid)
  s.fit_status = Status::TooFewPoints;
  s.fitted = false;
  s.accepted = false;
  s.candidate = false;
  s.bennett = BennettResult{};
  s.trace = EllipseTrace{};
}

bool errorAccepted(const EllipseOptions& o, const EllipseFit& fit, double mean_sampson_px) {
  return o.accept_rule == FitAcceptRule::RelativeError ? fit.relative_error <= o.max_relative_error
                                                       : mean_sampson_px <= o.max_sampson_distance_px;
}

bool isDarkSpotPath(const PathSummary& s, std::size_t pixels) {
  return pixels >= kMinSpotPixels && s.polarity > 0.0;
}

// Summarises every path into ws.paths (one cheap pass; no fit yet).
void summariseAll(const Paths& paths, EllipseWorkspace& ws) {
  const std::size_t count = paths.pathCount();
  ws.paths.resize(count);
  ws.dark.clear();
  for (std::size_t i = 0; i < count; ++i) {
    const auto path = paths.path(i);
    if (path.empty()) {
      ws.paths[i] = PathSummary{};
      continue;
    }
    summarise(path, ws.paths[i]);
    if (isDarkSpotPath(ws.paths[i], path.size())) ws.dark.push_back(i);
  }
}

// Fits path i once, if long enough. With the direct fit a path that passes the error
// screens (no pass over the points) becomes a candidate, decided by traceCandidate;
// Bennett decides here.
void fitPath(const EllipseOptions& o, const Paths& paths, std::size_t i, cv::Size image, EllipseWorkspace& ws) {
  PathSummary& s = ws.paths[i];
  if (s.fitted) return;
  s.fitted = true;
  const auto path = paths.path(i);
  if (path.size() < static_cast<std::size_t>(std::max(o.min_path_pixels, 6))) return;
  ConicMoments m;
  m.add(path);
  s.fit_status = fitEllipse(m, s.fit);
  if (!ok(s.fit_status)) return;  // no ellipse parameters for this path
  if (o.method == EllipseMethod::Bennett) {
    if (!ok(bennettAccumulate(path, o.bennett_max_points, ws.bennett, s.bennett, o.bennett_min_peak_fraction))) return;
    // The ellipse reported is the direct fit's: it must describe the path.
    s.accepted = bennettAccepts(o, s.bennett) && s.fit.relative_error <= o.bennett_max_relative_error;
    if (s.accepted) traceEllipse(s.fit, path, o.trace_inlier_px, image, s.trace);
    return;
  }
  if (o.accept_rule == FitAcceptRule::RelativeError && s.fit.relative_error > o.max_relative_error) return;
  if (o.accept_rule == FitAcceptRule::SampsonDistance && s.fit.taubin_px > kTaubinScreen * o.max_sampson_distance_px)
    return;
  s.candidate = true;
}

// The direct fit's decision on a candidate: the pass over its points.
bool traceCandidate(const EllipseOptions& o, std::span<const EdgePixel> path, cv::Size image, PathSummary& s) {
  if (!s.candidate) return s.accepted;
  s.candidate = false;
  traceEllipse(s.fit, path, o.trace_inlier_px, image, s.trace);
  s.fit.sampson_px = s.trace.mean_sampson_px;
  s.accepted = fitAccepted(o, s.fit, s.trace, o.min_traced_fraction);
  return s.accepted;
}

TargetDetection toDetection(const PathSummary& s, std::size_t index) {
  TargetDetection d;
  d.ellipse = s.fit.ellipse;
  d.conic = s.fit.conic;
  d.path_index = index;
  d.fit_error = s.fit.relative_error;
  d.sampson_px = s.trace.mean_sampson_px;
  d.traced = s.trace.traced;
  d.bennett_score = s.bennett.score;
  d.bennett_quality = s.bennett.quality;
  d.bennett_symmetry = s.bennett.symmetry_px;
  d.bbox = s.bbox;
  return d;
}

// Position of (x, y) in the frame where the ellipse is the unit circle.
Eigen::Vector2d unitFrame(const Ellipse& e, double x, double y) {
  const double t = e.angle_deg * kPi / 180.0;
  const double c = std::cos(t), s = std::sin(t);
  const double dx = x - e.cx, dy = y - e.cy;
  return {(dx * c + dy * s) / e.a, (-dx * s + dy * c) / e.b};
}

// Dark closed paths of spot size inside `e` (other than `self`) into ws.spots; true when a
// pair of them sits where the target's spots sit (the centre spot within the tolerance of
// the centre, the offset spot at its distance from it, within the tolerance too). spots[0]
// is then the centre spot. Other dark paths of spot size may lie on the disk (the end of a
// clamp or of tape, broken up by a local threshold), at most kMaxDiskBlobs in all: a
// photograph's texture inside a false ellipse holds many, and some pair of them would sit
// right by chance. Of several pairs that sit right, the best is taken only when it is
// clearly so (pairMisfit, by kClearlyBestPair).
bool findSpots(const EllipseOptions& o, const TargetGeometry& g, const Ellipse& e,
               std::size_t self, EllipseWorkspace& ws, std::array<std::size_t, 2>& spots) {
  ws.spots.clear();
  const double radius = std::sqrt(e.a * e.b);
  const double expected = g.spot_radius_mm / g.radius_mm * radius;
  for (const std::size_t j : ws.dark) {
    if (j == self) continue;
    const PathSummary& s = ws.paths[j];
    if (s.rms_radius < expected / kSpotSizeFactor || s.rms_radius > expected * kSpotSizeFactor) continue;
    if (unitFrame(e, s.cx, s.cy).norm() >= 1.0) continue;
    ws.spots.push_back(j);
    if (ws.spots.size() > kMaxDiskBlobs) return false;
  }
  if (ws.spots.size() < 2) return false;
  const double tol = o.target_spot_tolerance, offset = g.spot_offset_mm / g.radius_mm;
  auto at = [&](std::size_t j) { return unitFrame(e, ws.paths[j].cx, ws.paths[j].cy); };
  double best = std::numeric_limits<double>::infinity(), second = best;
  for (const std::size_t c : ws.spots) {
    const Eigen::Vector2d qc = at(c);
    if (qc.norm() > tol) continue;
    for (const std::size_t f : ws.spots) {
      const Eigen::Vector2d qf = at(f);
      // The offset spot lies farther out than the centre spot.
      const double apart = (qf - qc).norm();
      if (f == c || qf.norm() < qc.norm() || std::abs(apart - offset) > tol) continue;
      // Misfit: each measure in units of its tolerance; the spots are of one size.
      const double misfit = (qc.norm() + std::abs(apart - offset)) / tol +
                            std::abs(std::log(ws.paths[c].rms_radius / ws.paths[f].rms_radius)) / std::log(kSpotPairSizeRatio);
      if (misfit < best) {
        second = best;
        best = misfit;
        spots = {c, f};
      } else {
        second = std::min(second, misfit);
      }
    }
  }
  return std::isfinite(best) && second > best + kClearlyBestPair;
}

void holdSpots(TargetDetection& d, const std::array<std::size_t, 2>& spots, const EllipseWorkspace& ws) {
  d.spot_paths = spots;
  d.spot_boxes = {ws.paths[spots[0]].bbox, ws.paths[spots[1]].bbox};
  d.spots_found = true;
  const PathSummary& c = ws.paths[spots[0]];
  const PathSummary& f = ws.paths[spots[1]];
  d.spot_fraction = (unitFrame(d.ellipse, f.cx, f.cy) - unitFrame(d.ellipse, c.cx, c.cy)).norm();
}

// Is dark path j one of the spots of a target found already?
bool claimed(std::size_t j, const std::vector<TargetDetection>& found) {
  return std::any_of(found.begin(), found.end(), [&](const TargetDetection& d) {
    return d.spot_paths[0] == j || d.spot_paths[1] == j;
  });
}

// Could this path be the target? It must have a white interior and hold two dark paths
// of spot size within its bounding box, not counting the spots of targets found already.
bool mayHoldSpots(const TargetGeometry& g, std::size_t i, const EllipseWorkspace& ws,
                  const std::vector<TargetDetection>& found) {
  const PathSummary& s = ws.paths[i];
  if (!(s.polarity < 0.0)) return false;
  const double radius = 0.5 * std::sqrt(static_cast<double>(s.bbox.width) * s.bbox.height);
  const double expected = g.spot_radius_mm / g.radius_mm * radius;
  int count = 0;
  for (const std::size_t j : ws.dark) {
    const PathSummary& t = ws.paths[j];
    if (j == i) continue;
    if (t.rms_radius < expected / (2.0 * kSpotSizeFactor) || t.rms_radius > expected * 2.0 * kSpotSizeFactor)
      continue;
    if (!s.bbox.contains(cv::Point(static_cast<int>(t.cx), static_cast<int>(t.cy)))) continue;
    if (claimed(j, found)) continue;
    if (++count == 2) return true;
  }
  return false;
}

bool holdsDarkPath(const Ellipse& e, std::size_t self, const EllipseWorkspace& ws) {
  for (const std::size_t j : ws.dark) {
    if (j == self) continue;
    if (ws.paths[j].rms_radius < std::sqrt(e.a * e.b) && unitFrame(e, ws.paths[j].cx, ws.paths[j].cy).norm() < 1.0)
      return true;
  }
  return false;
}

// A pair of spots that proposes a rim (targetsFromSpots): the consensus takes only
// ellipses on which the pair sits where the target's spots sit, as findSpots will ask. An
// occluder's edge pulls a fit that is free of them off the rim (the spots then end up
// beyond findSpots' tolerance), or to a needle along its two straight edges.
struct RimAroundSpots {
  std::array<Eigen::Vector2d, 2> spots;
  double offset = 0.0;     // rf / R
  double tolerance = 0.0;  // EllipseOptions::target_spot_tolerance
};

bool holdsSpotsInPlace(const Ellipse& e, const RimAroundSpots& around) {
  const Eigen::Vector2d p = unitFrame(e, around.spots[0].x(), around.spots[0].y());
  const Eigen::Vector2d q = unitFrame(e, around.spots[1].x(), around.spots[1].y());
  return std::min(p.norm(), q.norm()) <= around.tolerance &&
         std::abs((p - q).norm() - around.offset) <= around.tolerance;
}

// The consensus ellipse of a path: the six-point fit whose ellipse the path traces most,
// refitted twice on its inliers (left in ws.inliers).
Status consensusFit(const EllipseOptions& o, std::span<const EdgePixel> path, EllipseWorkspace& ws,
                    EllipseFit& fit, const RimAroundSpots* around = nullptr) {
  ++ws.consensus_fits;
  const std::size_t n = path.size();
  if (n < 6) return Status::TooFewPoints;
  ws.rng.seed(static_cast<std::mt19937::result_type>(n));  // reproducible per path
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  const double inlier_px = o.trace_inlier_px;
  const double flattest = std::cos(o.target_max_tilt_deg * M_PI / 180.0);
  // Candidates are scored on an evenly spread subset of the path. The stride is odd:
  // CN1 lists a contour breadth first, alternating between its two fronts, so an even
  // stride would score one side of the contour only.
  const std::size_t stride = std::max<std::size_t>(1, n / kConsensusScorePoints) | 1;
  const std::size_t scored = (n + stride - 1) / stride;
  std::size_t best_count = 0;
  int best_covered = 0;
  double needed = o.robust_iterations;  // shrinks as the best inlier share grows
  EllipseFit best, trial;
  for (int it = 0; it < o.robust_iterations && it < needed; ++it) {
    std::array<std::size_t, 6> idx;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      bool fresh;
      do {
        idx[k] = pick(ws.rng);
        fresh = std::find(idx.begin(), idx.begin() + k, idx[k]) == idx.begin() + k;
      } while (!fresh);
    }
    ConicMoments m;
    for (std::size_t k : idx) m.add(path[k].x, path[k].y);
    if (!ok(fitEllipse(m, trial))) continue;
    // No circle is seen flatter than the steepest tilt allows: seeds on an occluder's two
    // straight edges fit a needle that their points trace whole.
    if (trial.ellipse.b < flattest * trial.ellipse.a) continue;
    if (around && !holdsSpotsInPlace(trial.ellipse, *around)) continue;
    // Score: how much of the candidate ellipse the path traces (an occluder's long
    // straight edges gather many inliers on a needle-thin ellipse but trace little of
    // it), then the inliers.
    std::size_t count = 0;
    std::uint64_t bins = 0;
    int covered = 0;
    const double th = trial.ellipse.angle_deg * kPi / 180.0;
    const double cs = std::cos(th), sn = std::sin(th);
    const double inv_a = 1.0 / trial.ellipse.a, inv_b = 1.0 / trial.ellipse.b;
    const SampsonBand band(trial, inlier_px);
    std::size_t left = scored;  // points still to score
    for (std::size_t k = 0; k < n; k += stride, --left) {
      // Each point sets at most one bin: a trial that cannot reach the best's coverage
      // any more cannot win.
      if (covered + static_cast<int>(left) < best_covered) break;
      const double x = path[k].x, y = path[k].y;
      if (!band.holds(x, y)) continue;
      ++count;
      const double dx = x - trial.ellipse.cx, dy = y - trial.ellipse.cy;
      const double t = fastAtan2((-dx * sn + dy * cs) * inv_b, (dx * cs + dy * sn) * inv_a);
      const std::uint64_t bin = std::uint64_t{1} << std::min(63, static_cast<int>((t + kPi) / (2.0 * kPi) * 64.0));
      covered += (bins & bin) == 0;
      bins |= bin;
    }
    if (covered > best_covered || (covered == best_covered && count > best_count)) {
      best_covered = covered;
      best_count = count;
      best = trial;
      // Iterations for a 99 % chance of one all-inlier sample at this share, taken as
      // the smaller of the inlier share and the share of the ellipse traced: a wrong
      // ellipse through part of the arc and an occluder's edge gathers many inliers,
      // and stopping on their share alone ends the search before the true one is drawn.
      const double share = std::min(static_cast<double>(count) / scored, covered / 64.0);
      const double clean = std::pow(share, 6.0);
      if (clean >= 1.0) break;
      if (clean > 0.0) needed = std::log(0.01) / std::log1p(-clean);
    }
  }
  best_count = 0;
  if (best_covered > 0) {
    const SampsonBand band(best, inlier_px);
    for (const EdgePixel& p : path) best_count += band.holds(p.x, p.y);
  }
  if (best_count < 6) return Status::NotAnEllipse;
  // Refit on the inliers, twice: the consensus ellipse is only as good as six points.
  for (int round = 0; round < 2; ++round) {
    ws.inliers.clear();
    const SampsonBand band(best, inlier_px);
    for (const EdgePixel& p : path)
      if (band.holds(p.x, p.y)) ws.inliers.push_back(p);
    ConicMoments m;
    m.add(std::span<const EdgePixel>(ws.inliers));
    const Status st = fitEllipse(m, trial);
    if (!ok(st)) return st;
    best = trial;
  }
  // The refit may flatten a rounder sample's ellipse back into the needle.
  if (best.ellipse.b < flattest * best.ellipse.a) return Status::NotAnEllipse;
  fit = best;
  return Status::Ok;
}

// Could this path, which failed the plain fit, be an occluded target? Its plain fit
// gave an ellipse, and that ellipse, grown by kOccludedReach, holds a pair of dark paths
// that could be the spots: of the same size within kSpotPairSizeRatio (the spots are
// equal; perspective and digitisation part their images by a few per cent, 1.05 on
// the tests' occluded targets), as far apart as the spots are for their size (rf / r0,
// foreshortened or stretched by up to kSpotPairSlack), and not the spots of a target
// found already. Clutter paths that only pass mayHoldSpots (their box spans the target)
// pair dark blobs of unequal sizes (1.34-2.4 on the benchmark frames) or hold the found
// target's spots; this keeps the consensus fit to the paths that can be a target, none
// in the common frame.
constexpr double kOccludedReach = 1.5;
constexpr double kSpotPairSlack = 2.0;

// Could dark paths p and q be the target's two spots? The same size within
// kSpotPairSizeRatio, and as far apart as the spots are for their size (rf / r0,
// foreshortened or stretched by up to kSpotPairSlack).
bool spotPair(const TargetGeometry& g, const PathSummary& p, const PathSummary& q) {
  if (std::max(p.rms_radius, q.rms_radius) > kSpotPairSizeRatio * std::min(p.rms_radius, q.rms_radius)) return false;
  const double ratio = g.spot_offset_mm / g.spot_radius_mm;
  const double apart = std::hypot(p.cx - q.cx, p.cy - q.cy) / (0.5 * (p.rms_radius + q.rms_radius));
  return apart >= ratio / kSpotPairSlack && apart <= ratio * kSpotPairSlack;
}

bool mayBeOccludedTarget(const TargetGeometry& g, std::size_t i, const EllipseWorkspace& ws,
                         const std::vector<TargetDetection>& found) {
  const PathSummary& s = ws.paths[i];
  if (!ok(s.fit_status)) return false;
  const Ellipse& e = s.fit.ellipse;
  const double expected = g.spot_radius_mm / g.radius_mm * std::sqrt(e.a * e.b);
  auto candidate = [&](std::size_t j) {
    const PathSummary& t = ws.paths[j];
    return j != i && t.rms_radius >= expected / (2.0 * kSpotSizeFactor) &&
           t.rms_radius <= expected * 2.0 * kSpotSizeFactor && unitFrame(e, t.cx, t.cy).norm() < kOccludedReach &&
           !claimed(j, found);
  };
  for (std::size_t a = 0; a < ws.dark.size(); ++a) {
    if (!candidate(ws.dark[a])) continue;
    for (std::size_t b = a + 1; b < ws.dark.size(); ++b)
      if (candidate(ws.dark[b]) && spotPair(g, ws.paths[ws.dark[a]], ws.paths[ws.dark[b]])) return true;
  }
  return false;
}

// The pixels of other white paths that lie on `fit`'s ellipse (within the inlier band,
// gradient pointing into the ellipse) join ws.inliers: an occluder that crosses the disk
// splits its outline into several paths, each tracing only part of the ellipse.
// Returns the number of pixels added.
std::size_t gatherOtherPaths(const EllipseOptions& o, const Paths& paths, std::size_t self, const EllipseFit& fit,
                             EllipseWorkspace& ws) {
  const Ellipse& e = fit.ellipse;
  const double reach = e.a + 2.0 * o.trace_inlier_px;
  const cv::Rect box(static_cast<int>(std::floor(e.cx - reach)), static_cast<int>(std::floor(e.cy - reach)),
                     static_cast<int>(2.0 * reach) + 2, static_cast<int>(2.0 * reach) + 2);
  std::size_t added = 0;
  const SampsonBand band(fit, o.trace_inlier_px);
  for (std::size_t j = 0; j < ws.paths.size(); ++j) {
    const PathSummary& t = ws.paths[j];
    if (j == self || !(t.polarity < 0.0) || (t.bbox & box).area() == 0) continue;
    for (const EdgePixel& p : paths.path(j)) {
      if (!band.holds(p.x, p.y)) continue;
      if (p.gx * (p.x - e.cx) + p.gy * (p.y - e.cy) >= 0.0) continue;  // gradient points outwards
      ws.inliers.push_back(p);
      ++added;
    }
  }
  return added;
}

// The robust pass on path i: the consensus fit of the path, and when its inliers trace
// too little of the ellipse, the same ellipse's pixels on the other paths with them.
Status robustTarget(const EllipseOptions& o, const Paths& paths, std::size_t i, cv::Size image,
                    EllipseWorkspace& ws, EllipseFit& fit, EllipseTrace& trace) {
  if (const Status st = consensusFit(o, paths.path(i), ws, fit); !ok(st)) return st;
  traceEllipse(fit, ws.inliers, o.trace_inlier_px, image, trace);
  fit.sampson_px = trace.mean_sampson_px;
  if (fitAccepted(o, fit, trace, o.robust_min_traced_fraction)) return Status::Ok;
  // Refit on the union twice, as the consensus did on the path alone.
  for (int round = 0; round < 2; ++round) {
    ws.inliers.clear();
    const SampsonBand band(fit, o.trace_inlier_px);
    for (const EdgePixel& p : paths.path(i))
      if (band.holds(p.x, p.y)) ws.inliers.push_back(p);
    if (gatherOtherPaths(o, paths, i, fit, ws) == 0) return Status::NotAnEllipse;
    ConicMoments m;
    m.add(std::span<const EdgePixel>(ws.inliers));
    if (const Status st = fitEllipse(m, fit); !ok(st)) return st;
  }
  traceEllipse(fit, ws.inliers, o.trace_inlier_px, image, trace);
  fit.sampson_px = trace.mean_sampson_px;
  return fitAccepted(o, fit, trace, o.robust_min_traced_fraction) ? Status::Ok : Status::NotAnEllipse;
}

// Pairs of dark paths that may be the spots, tried at most, the likeliest first. A printed
// photograph's text or foliage gives a thousand pairs, and fragments that an occluder cuts
// from the card round the spots can rank the target's pair past the hundredth; each try
// costs only the gathering of edge pixels unless its seeds lie on a smooth outline.
constexpr int kMaxSpotPairs = 128;
// Other dark paths of the spots' size within this many times the spots' distance of their
// midpoint count against a pair: inside the disk, clear of the rim.
constexpr double kSpotPairRoundness = 1.2;
// Neighbouring directions' nearest edges on one rim differ by at most this share (a circle
// seen at 60 deg, 64 directions: under 6 %) and a pixel; at least this share of the
// directions must be so before the seeds are fitted.
constexpr double kSeedStep = 0.15;
constexpr double kSmoothSeeds = 0.5;
// Paths whose box is at most this wide are found by their box's left edge (targetsFromSpots).
constexpr int kNarrowPathPx = 64;
// The seeds' consensus: with the robust pass's least share of them on the rim (0.75), a
// clean six-point sample comes in 60 tries but for once in ten thousand.
constexpr int kSeedIterations = 60;
// The rim lies within this many times its radius, as the spots measure it, of their midpoint,
// and beyond this many times the spots' distance.
constexpr double kRimReach = 1.6;
constexpr double kRimBeyondSpots = 0.7;
// With both spots where the target has them, a rim traced over this share (or the robust
// pass's, if less) is the target's: tape crossing the rim at a slant hides a long arc.
constexpr double kSpotsMinTraced = 0.6;
// A rim traced this far from a pair of spots is taken without trying the other pairs.
constexpr double kSpotsSureTraced = 0.9;
// The spots' size within this factor of r0 / R times the rim's (findSpots allows 2.5), or
// down to kSpotsShrunk below it: a local threshold keeps only the core of a blurred spot on
// dim paper (0.54 of its size on a webcam still at 2 m).
constexpr double kSpotsSizeMatch = 1.6;
constexpr double kSpotsShrunk = 2.2;

// The pairs of dark paths that may be a target's spots (spotPair, neither a found target's),
// into ws.pairs, the likeliest first: fewest other dark paths of their size round them (the
// spots lie on clean paper; a photograph's texture crowds its blobs), then the most equal in
// size. The paths are swept in order of x, so only neighbours are compared.
void listSpotPairs(const TargetGeometry& g, EllipseWorkspace& ws, const std::vector<TargetDetection>& found) {
  ws.pairs.clear();
  ws.by_x.assign(ws.dark.begin(), ws.dark.end());
  std::sort(ws.by_x.begin(), ws.by_x.end(), [&](std::size_t i, std::size_t j) { return ws.paths[i].cx < ws.paths[j].cx; });
  const double ratio = g.spot_offset_mm / g.spot_radius_mm;
  auto firstAtOrAfter = [&](double x) {
    return std::lower_bound(ws.by_x.begin(), ws.by_x.end(), x,
                            [&](std::size_t j, double v) { return ws.paths[j].cx < v; });
  };
  for (auto ia = ws.by_x.begin(); ia != ws.by_x.end(); ++ia) {
    const PathSummary& p = ws.paths[*ia];
    if (claimed(*ia, found)) continue;
    // Two spots lie at most ratio * slack times their mean size apart, and the other one is
    // at most kSpotPairSizeRatio times this one's size.
    const double most = ratio * kSpotPairSlack * 0.5 * (1.0 + kSpotPairSizeRatio) * p.rms_radius;
    for (auto ib = ia + 1; ib != ws.by_x.end() && ws.paths[*ib].cx - p.cx <= most; ++ib) {
      const PathSummary& q = ws.paths[*ib];
      if (claimed(*ib, found) || !spotPair(g, p, q)) continue;
      const double mx = 0.5 * (p.cx + q.cx), my = 0.5 * (p.cy + q.cy);
      const double round = kSpotPairRoundness * std::hypot(p.cx - q.cx, p.cy - q.cy);
      const double size = 0.5 * (p.rms_radius + q.rms_radius);
      int others = 0;
      for (auto k = firstAtOrAfter(mx - round); k != ws.by_x.end() && ws.paths[*k].cx <= mx + round; ++k) {
        const PathSummary& t = ws.paths[*k];
        if (*k == *ia || *k == *ib || t.rms_radius < size / kSpotSizeFactor || t.rms_radius > size * kSpotSizeFactor)
          continue;
        others += std::hypot(t.cx - mx, t.cy - my) <= round;
      }
      ws.pairs.push_back({others, std::abs(std::log(p.rms_radius / q.rms_radius)), *ia, *ib});
    }
  }
  std::sort(ws.pairs.begin(), ws.pairs.end());
}

// The target found from a pair of spots when no path outlines its rim (detect.h). Every
// other path's edge pixels within reach of the pair whose gradient points towards it
// (brighter inside) are gathered; in each of kSeedArcs directions about the pair the
// nearest of them beyond the spots is where the rim would be, and the consensus fit of those
// few seeds (cheap: one point a direction) proposes the rim. All gathered pixels on it are
// then fitted twice, and the ellipse accepted as the robust pass accepts one (over
// kSpotsMinTraced of it traced), holding exactly that pair as its spots.
void targetsFromSpots(const EllipseOptions& o, const TargetGeometry& g, const Paths& paths, cv::Size image,
                      EllipseWorkspace& ws, std::vector<TargetDetection>& out) {
  listSpotPairs(g, ws, out);
  if (ws.pairs.empty()) return;
  // Paths by the left edge of their box, so that a pair visits only those near it; the few
  // wider than kNarrowPathPx (the scene's long outlines) are visited always.
  ws.narrow_by_x.clear();
  ws.wide.clear();
  for (std::size_t j = 0; j < ws.paths.size(); ++j)
    (ws.paths[j].bbox.width <= kNarrowPathPx ? ws.narrow_by_x : ws.wide).push_back(j);
  std::sort(ws.narrow_by_x.begin(), ws.narrow_by_x.end(),
            [&](std::size_t i, std::size_t j) { return ws.paths[i].bbox.x < ws.paths[j].bbox.x; });
  std::array<std::size_t, 2> spots;
  std::array<EdgePixel, kSeedArcs> nearest;
  std::array<double, kSeedArcs> nearest_d2;
  const double min_traced = std::min(o.robust_min_traced_fraction, kSpotsMinTraced);
  EllipseOptions seeding = o;
  seeding.robust_iterations = std::min(o.robust_iterations, kSeedIterations);
  const std::size_t tries = std::min(ws.pairs.size(), static_cast<std::size_t>(kMaxSpotPairs));
  std::optional<TargetDetection> best;
  for (std::size_t t = 0; t < tries; ++t) {
    const std::size_t a = ws.pairs[t].a, b = ws.pairs[t].b;
    if (claimed(a, out) || claimed(b, out)) continue;
    const PathSummary &p = ws.paths[a], &q = ws.paths[b];
    // The rim's radius by the spots' size (R / r0) and by their distance (R / rf): a tilt
    // shortens either, the distance only along one direction, so the larger one is taken.
    const double apart = std::hypot(p.cx - q.cx, p.cy - q.cy);
    const double rim = std::max(0.5 * (p.rms_radius + q.rms_radius) * g.radius_mm / g.spot_radius_mm,
                                apart * g.radius_mm / g.spot_offset_mm);
    const double mx = 0.5 * (p.cx + q.cx), my = 0.5 * (p.cy + q.cy), reach = kRimReach * rim;
    // The rim lies at least (R - rf / 2) / R of its minor axis from the pair's midpoint, and
    // the minor axis is at least half the major one up to 60 deg of tilt.
    const double beyond = kRimBeyondSpots * apart;
    const cv::Rect box(static_cast<int>(std::floor(mx - reach)), static_cast<int>(std::floor(my - reach)),
                       static_cast<int>(2.0 * reach) + 2, static_cast<int>(2.0 * reach) + 2);
    ws.gathered.clear();
    ws.gathered_counts.assign(ws.paths.size(), 0);
    nearest_d2.fill(std::numeric_limits<double>::infinity());
    auto gather = [&](std::size_t j) {
      if (j == a || j == b || (ws.paths[j].bbox & box).area() == 0) return;
      for (const EdgePixel& e : paths.path(j)) {
        const double dx = e.x - mx, dy = e.y - my, d2 = dx * dx + dy * dy;
        if (d2 > reach * reach || e.gx * dx + e.gy * dy >= 0.0) continue;
        ws.gathered.push_back(e);
        ++ws.gathered_counts[j];
        if (d2 < beyond * beyond) continue;
        const int arc = std::min(kSeedArcs - 1, static_cast<int>((fastAtan2(dy, dx) + kPi) / (2.0 * kPi) * kSeedArcs));
        if (d2 < nearest_d2[arc]) {
          nearest_d2[arc] = d2;
          nearest[arc] = e;
        }
      }
    };
    for (const std::size_t j : ws.wide) gather(j);
    for (auto j = std::lower_bound(ws.narrow_by_x.begin(), ws.narrow_by_x.end(), box.x - kNarrowPathPx,
                                   [&](std::size_t i, int x) { return ws.paths[i].bbox.x < x; });
         j != ws.narrow_by_x.end() && ws.paths[*j].bbox.x <= box.x + box.width; ++j)
      gather(*j);
    ws.seeds.clear();
    for (int k = 0; k < kSeedArcs; ++k)
      if (std::isfinite(nearest_d2[k])) ws.seeds.push_back(nearest[k]);
    if (ws.seeds.size() < static_cast<std::size_t>(min_traced * kSeedArcs)) continue;
    // A rim round the pair is a smooth outline: the nearest edge moves little from one
    // direction to the next, while a photograph's texture scatters it. Without that, no
    // consensus fit (the costly part) is tried.
    int smooth = 0;
    for (int k = 0; k < kSeedArcs; ++k) {
      const double r0 = std::sqrt(nearest_d2[k]), r1 = std::sqrt(nearest_d2[(k + 1) % kSeedArcs]);
      smooth += std::isfinite(r0) && std::isfinite(r1) && std::abs(r0 - r1) <= kSeedStep * std::min(r0, r1) + 1.0;
    }
    if (smooth < static_cast<int>(kSmoothSeeds * kSeedArcs)) continue;
    EllipseFit fit;
    EllipseTrace trace;
    const RimAroundSpots around{{Eigen::Vector2d(p.cx, p.cy), Eigen::Vector2d(q.cx, q.cy)},
                                g.spot_offset_mm / g.radius_mm, o.target_spot_tolerance};
    if (!ok(consensusFit(seeding, ws.seeds, ws, fit, &around))) continue;
    // Every gathered pixel on the proposed rim, fitted twice.
    bool fitted = true;
    for (int round = 0; round < 2 && fitted; ++round) {
      ws.inliers.clear();
      const SampsonBand band(fit, o.trace_inlier_px);
      for (const EdgePixel& e : ws.gathered)
        if (band.holds(e.x, e.y)) ws.inliers.push_back(e);
      ConicMoments m;
      m.add(std::span<const EdgePixel>(ws.inliers));
      fitted = ok(fitEllipse(m, fit));
    }
    if (!fitted) continue;
    traceEllipse(fit, ws.inliers, o.trace_inlier_px, image, trace);
    fit.sampson_px = trace.mean_sampson_px;
    if (!fitAccepted(o, fit, trace, min_traced)) continue;
    if (!plausibleTargetView(o, fit.ellipse, image)) continue;
    if (!findSpots(o, g, fit.ellipse, kNoPath, ws, spots)) continue;
    if (!((spots[0] == a && spots[1] == b) || (spots[0] == b && spots[1] == a))) continue;
    // The spots' size must be the target's for this rim, closer than findSpots asks: a
    // photograph's blobs with arcs round them are of any size.
    const double expected = g.spot_radius_mm / g.radius_mm * std::sqrt(fit.ellipse.a * fit.ellipse.b);
    if (std::max(p.rms_radius, q.rms_radius) > kSpotsSizeMatch * expected ||
        std::min(p.rms_radius, q.rms_radius) < expected / kSpotsShrunk)
      continue;
    PathSummary s;
    s.fit = fit;
    s.trace = trace;
    int x0 = image.width, y0 = image.height, x1 = -1, y1 = -1;
    for (const EdgePixel& e : ws.inliers) {
      x0 = std::min<int>(x0, e.x), y0 = std::min<int>(y0, e.y);
      x1 = std::max<int>(x1, e.x), y1 = std::max<int>(y1, e.y);
    }
    s.bbox = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
    const auto most = std::max_element(ws.gathered_counts.begin(), ws.gathered_counts.end());
    TargetDetection d = toDetection(s, static_cast<std::size_t>(most - ws.gathered_counts.begin()));
    holdSpots(d, spots, ws);
    d.robust = true;
    if (o.report_all_targets) {
      out.push_back(d);
      continue;
    }
    // One target wanted: the one whose rim is traced most (a photograph's texture may hold
    // pairs with arcs round them, seldom traced as far); one traced almost whole ends the search.
    if (!best || d.traced > best->traced) best = d;
    if (d.traced >= kSpotsSureTraced) break;
  }
  if (best) out.push_back(*best);
}

}  // namespace

bool fitAccepted(const EllipseOptions& o, const EllipseFit& fit, const EllipseTrace& trace,
                 double min_traced_fraction) {
  return errorAccepted(o, fit, trace.mean_sampson_px) &&
         trace.traced >= min_traced_fraction * trace.observable - 1e-12 && trace.traced >= o.min_arc_fraction;
}

Status detectEllipses(const EllipseOptions& o, const Paths& paths, cv::Size image, EllipseWorkspace& ws,
                      std::vector<TargetDetection>& out) {
  out.clear();
  summariseAll(paths, ws);
  for (std::size_t i = 0; i < ws.paths.size(); ++i) {
    fitPath(o, paths, i, image, ws);
    if (traceCandidate(o, paths.path(i), image, ws.paths[i])) out.push_back(toDetection(ws.paths[i], i));
  }
  return out.empty() ? Status::NoTarget : Status::Ok;
}

Status fitEllipseRobust(const EllipseOptions& o, std::span<const EdgePixel> path, cv::Size image,
                        EllipseWorkspace& ws, EllipseFit& fit, EllipseTrace& trace) {
  if (const Status st = consensusFit(o, path, ws, fit); !ok(st)) return st;
  traceEllipse(fit, ws.inliers, o.trace_inlier_px, image, trace);
  fit.sampson_px = trace.mean_sampson_px;
  return fitAccepted(o, fit, trace, o.robust_min_traced_fraction) ? Status::Ok : Status::NotAnEllipse;
}

bool plausibleTargetView(const EllipseOptions& o, const Ellipse& e, cv::Size image) {
  // A circle tilted by t from the line of sight is seen as an ellipse of axis ratio about
  // cos t (exactly so far from the camera; perspective only rounds it).
  if (!(e.a > 0.0) || e.b < std::cos(o.target_max_tilt_deg * M_PI / 180.0) * e.a) return false;
  if (image.empty()) return true;
  return e.cx >= 0.0 && e.cy >= 0.0 && e.cx <= image.width - 1.0 && e.cy <= image.height - 1.0;
}

Status detectTarget(const EllipseOptions& o, const TargetGeometry& g, const Paths& paths, cv::Size image,
                    EllipseWorkspace& ws, std::vector<TargetDetection>& out) {
  out.clear();
  ws.runners_up.clear();
  ws.consensus_fits = 0;
  summariseAll(paths, ws);
  // Only a white path with two dark paths of spot size inside its box can be the target:
  // only such paths are fitted first, and only if their ellipse holds the spots is its
  // contour traced. They are taken smallest box first, so the target's rim comes before
  // the clutter whose box spans the target, and a path whose box holds no spots but a
  // found target's is not fitted at all.
  std::array<std::size_t, 2> spots;
  const std::size_t min_pixels = static_cast<std::size_t>(std::max(o.min_path_pixels, 6));
  ws.order.clear();
  for (std::size_t i = 0; i < ws.paths.size(); ++i)
    if (paths.path(i).size() >= min_pixels && mayHoldSpots(g, i, ws, out)) ws.order.push_back(i);
  std::sort(ws.order.begin(), ws.order.end(), [&](std::size_t a, std::size_t b) {
    const int area_a = ws.paths[a].bbox.area(), area_b = ws.paths[b].bbox.area();
    return area_a != area_b ? area_a < area_b : a < b;
  });
  for (const std::size_t i : ws.order) {
    PathSummary& s = ws.paths[i];
    if (!out.empty() && !mayHoldSpots(g, i, ws, out)) continue;
    fitPath(o, paths, i, image, ws);
    if (!(s.accepted || s.candidate)) continue;
    if (!plausibleTargetView(o, s.fit.ellipse, image)) continue;
    if (!findSpots(o, g, s.fit.ellipse, i, ws, spots)) continue;
    if (!traceCandidate(o, paths.path(i), image, s)) continue;
    TargetDetection d = toDetection(s, i);
    holdSpots(d, spots, ws);
    out.push_back(d);
  }
  // Every spot-holding path that failed the plain fit, also when a target was found
  // above: a second, occluded target must make the frame ambiguous, not vanish.
  if (o.robust_fit && o.method == EllipseMethod::DirectFit) {
    for (std::size_t i = 0; i < ws.paths.size(); ++i) {
      PathSummary& s = ws.paths[i];
      if (!s.fitted || s.accepted) continue;  // fitted above: the paths that may hold spots
      if (s.candidate && traceCandidate(o, paths.path(i), image, s)) continue;  // accepted: holds no spots
      if (!mayBeOccludedTarget(g, i, ws, out)) continue;
      EllipseFit fit;
      EllipseTrace trace;
      if (!ok(robustTarget(o, paths, i, image, ws, fit, trace))) continue;
      if (!plausibleTargetView(o, fit.ellipse, image)) continue;
      if (!findSpots(o, g, fit.ellipse, i, ws, spots)) continue;
      // The same spots as a target found already: the same target.
      const bool seen = std::any_of(out.begin(), out.end(), [&](const TargetDetection& d) {
        return std::find_first_of(d.spot_paths.begin(), d.spot_paths.end(), spots.begin(), spots.end()) !=
               d.spot_paths.end();
      });
      if (seen) continue;
      s.fit = fit;
      s.trace = trace;
      TargetDetection d = toDetection(s, i);
      holdSpots(d, spots, ws);
      d.robust = true;
      out.push_back(d);
    }
  }
  if (out.empty() && o.robust_fit && o.targets_from_spots && o.method == EllipseMethod::DirectFit)
    targetsFromSpots(o, g, paths, image, ws, out);
  if (out.size() == 1) return Status::Ok;
  // Several targets: in path order, whichever pass found them.
  std::sort(out.begin(), out.end(),
            [](const TargetDetection& a, const TargetDetection& b) { return a.path_index < b.path_index; });
  if (out.size() > 1) return o.report_all_targets ? Status::Ok : Status::AmbiguousTarget;
  if (o.require_target_spots) return Status::NoTarget;

  // The thesis's choice among plain ellipses: lowest error (fit) or highest score (Bennett),
  // ellipses that hold some dark path first. The runners-up, in the same order, go to
  // ws.runners_up.
  ws.ranked.clear();
  for (std::size_t i = 0; i < ws.paths.size(); ++i) {
    PathSummary& s = ws.paths[i];
    if (!(s.polarity < 0.0)) continue;
    fitPath(o, paths, i, image, ws);
    if (!traceCandidate(o, paths.path(i), image, s)) continue;
    if (!plausibleTargetView(o, s.fit.ellipse, image)) continue;
    const bool holds = holdsDarkPath(s.fit.ellipse, i, ws);
    double key;
    if (o.method == EllipseMethod::Bennett) key = -s.bennett.score;
    else if (o.accept_rule == FitAcceptRule::RelativeError) key = s.fit.relative_error;
    else key = s.trace.mean_sampson_px;
    ws.ranked.push_back({!holds, key, i});
  }
  if (ws.ranked.empty()) return Status::NoTarget;
  const std::size_t ranked = std::min(ws.ranked.size(), kRunnersUp + 1);
  std::partial_sort(ws.ranked.begin(), ws.ranked.begin() + static_cast<std::ptrdiff_t>(ranked), ws.ranked.end());
  out.push_back(toDetection(ws.paths[ws.ranked[0].path], ws.ranked[0].path));
  for (std::size_t r = 1; r < ranked; ++r) {
    const std::size_t path = ws.ranked[r].path;
    ws.runners_up.push_back(toDetection(ws.paths[path], path));
  }
  return Status::Ok;
}

}  // namespace imagepro
