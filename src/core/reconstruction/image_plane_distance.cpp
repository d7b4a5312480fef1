#include "core/reconstruction/image_plane_distance.h"

#include <cmath>

namespace imagepro {

Status estimateImagePlaneDistance(double focal_length_mm,
                                  const std::function<Status(double d0_mm, double& depth_mm)>& depthAt,
                                  double epsilon_mm, int max_iterations, ImagePlaneDistanceEstimate& out) {
  if (!(focal_length_mm > 0.0) || !(epsilon_mm > 0.0) || max_iterations < 1 || !depthAt)
    return Status::InvalidSettings;
  const double f = focal_length_mm;  // d0(1)
  double d0 = f;
  out.history_mm.assign(1, f);
  for (int i = 1; i <= max_iterations; ++i) {
    double depth = 0.0;
    if (const Status s = depthAt(d0, depth); !ok(s)) return s;
    if (!(depth > f) || !std::isfinite(depth)) return Status::Diverged;
    const double next = depth * f / (depth - f);  // eq. 4.1
    out.iterations = i;
    out.d0_mm = next;
    out.depth_mm = depth;
    out.history_mm.push_back(next);
    if (std::abs(next - d0) < epsilon_mm) {  // eq. 4.2
      // The depth that goes with the converged d0.
      if (const Status s = depthAt(next, depth); !ok(s)) return s;
      out.depth_mm = depth;
      return Status::Ok;
    }
    d0 = next;
  }
  return Status::Diverged;
}

}  // namespace imagepro
