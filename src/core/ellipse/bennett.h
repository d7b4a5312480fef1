#pragma once
// Bennett's ellipse detection as the thesis re-implemented it (thesis 2.6.1,
// eqs. 2.26-2.28): one accumulator per connected path. Two edge points P1, P2 with
// their tangent lines I1, I2 define the family of conics L^2 - lambda I1 I2 = 0
// (L the chord P1P2). A, the quadratic part, is positive definite for lambda between 0
// and a bound that depends on the pair; over that range the centre runs along the ray
// that starts at the chord's midpoint M and leads away from T, the intersection of the
// tangents (for parallel tangents it stays at M). Every pair adds one vote to each
// accumulator cell on its ray, so a cell's score is the number of pairs that admit an
// ellipse centred there. Pairs whose Sobel gradients point to opposite sides of the
// chord (no ellipse with one interior has both tangents) are skipped.
//
// The absolute peak gives the score, the quality factor (score divided by the square
// root of the radius of the circle on which the mean score is half the peak) and the
// symmetry measure (the radius at which the accumulator stops being point-symmetric
// about the peak). The decision rules of 2.6.1 are in bennettAccepts.
//
// Two departures from the thesis, both for speed, neither changing the peak:
//  * the accumulator covers the path's bounding box (plus a margin) instead of the whole
//    image. The centre of a closed path lies inside its box, and the box of a
//    point-symmetric path is symmetric about its centre, so rule 1 ("the symmetry must
//    not vanish closer than the closest image border") becomes: the accumulator is
//    point-symmetric about the peak over the whole box, cells outside it counting as
//    empty. A peak within two cells of the box's centre is taken at the centre (the
//    rays' rounding moves the peak of a symmetric path by a cell); a peak elsewhere
//    loses its symmetry where the mirrored cells leave the box;
//  * a path with more than max_points pixels with a gradient votes with a uniformly
//    random sample of max_points of them (fixed seed; not an even stride, which would
//    take one front of a contour listed breadth first) and each vote weighs
//    (n (n-1)) / (m (m-1)), so scores estimate the all-pairs score.
// The pair set-up, the ray walk and the peak search run on vector lanes (AVX/AVX2 where
// the processor has them, else SSE2 and scalar; bennett_rays_pass.inc) and count exactly what
// the one-cell-at-a-time definition counts.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/common/status.h"
#include "core/edges/edge_list.h"
#include "core/settings/options.h"

namespace imagepro {

struct BennettResult {
  double score = 0.0;            // accumulator value at the absolute peak
  double quality = 0.0;          // score / sqrt(half-score radius)
  double half_radius_px = 0.0;   // radius of the circle with mean score = score / 2
  double symmetry_px = 0.0;      // radius at which point symmetry about the peak vanishes
  double border_distance_px = 0.0;  // from the peak to the farthest accumulator border
  double cx = 0.0, cy = 0.0;     // centre of symmetry of the peak (pixels)
  double peak_fraction = 0.0;    // score / all pairs of the path's pixels with a gradient
  std::size_t pairs = 0;         // point pairs that voted
};

struct BennettWorkspace {
  struct Ray {
    std::int32_t x, y, sx, sy;  // first cell and step, 16.16 fixed point
    std::int32_t count;         // cells
  };
  std::vector<std::uint32_t> accumulator;  // votes per cell, row by row over `box`
  // The image pixels the accumulator covers: cell (i, j) is pixel (x0 + i, y0 + j).
  struct Box {
    int x0 = 0, y0 = 0, width = 0, height = 0;
  } box;
  std::vector<double> points;  // the sampled pixels: x, y, gx, gy and c of g . X = c, m each
  std::vector<Ray> rays;                   // the clipped rays of one pixel's pairs
  std::vector<std::int32_t> cells;         // the accumulator indices of one ray's cells
  std::vector<std::uint32_t> sample;  // indices of the sampled path pixels
  std::vector<std::int64_t> rings;     // per-ring sums about the peak
};

// TooFewPoints for fewer than 6 pixels with a gradient, NoTarget when no pair votes.
// screen_peak_fraction > 0 (the decision rule's minimum peak share): the path is first
// accumulated from half its sampled pixels, and if that peak gathers less than half
// the share the full accumulation is skipped (out then has the coarse score and share,
// and no symmetry: never accepted). Most non-elliptical paths stop there.
Status bennettAccumulate(std::span<const EdgePixel> path, int max_points, BennettWorkspace& ws, BennettResult& out,
                         double screen_peak_fraction = 0.0);

// The thesis's decision rules 1-3 (rule 4, the highest score among the accepted paths,
// is the caller's): symmetry reaching the accumulator border, quality and score within
// their ranges; and, measured on the synthetic library, a peak that gathers at least
// bennett_min_peak_fraction of the path's pairs (the raw score grows with the path's
// length, this share does not).
bool bennettAccepts(const EllipseOptions& options, const BennettResult& r);

}  // namespace imagepro
