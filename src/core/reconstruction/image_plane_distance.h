#pragma once
// Image plane distance d0 from a target at an unknown depth (thesis 4.1, eqs. 4.1-4.2).
// A lens of focal length f focused on an object at depth d forms its image at
// d0 = f d / (d - f) (thin lens), while the depth reconstructed from the image itself
// scales with the d0 assumed. Starting from d0(1) = f, the thesis iterates
//     d0(i+1) = d(d0(i)) d0(1) / (d(d0(i)) - d0(1))                         (4.1)
// until |d0(i+1) - d0(i)| < epsilon                                          (4.2).
// Since d changes about in proportion to d0 and d >> f, each step shrinks the error by
// about (f/d)^2: two or three steps reach 1e-6 mm.
#include <functional>
#include <vector>

#include "core/common/status.h"

namespace imagepro {

struct ImagePlaneDistanceEstimate {
  double d0_mm = 0.0;     // the converged image plane distance
  double depth_mm = 0.0;  // the target's depth reconstructed with it
  int iterations = 0;     // evaluations of eq. 4.1
  std::vector<double> history_mm;  // d0(1) = f, then d0 after each step: the iteration converging
};

// `depthAt(d0, depth)` reconstructs the target's depth (mm along the optical axis) with
// image plane distance d0; its failure ends the estimate with its status. InvalidSettings
// for a non-positive focal length, epsilon or iteration limit; Diverged when a depth is
// not beyond the focal length (no real image) or the limit is reached first.
Status estimateImagePlaneDistance(double focal_length_mm,
                                  const std::function<Status(double d0_mm, double& depth_mm)>& depthAt,
                                  double epsilon_mm, int max_iterations, ImagePlaneDistanceEstimate& out);

}  // namespace imagepro
