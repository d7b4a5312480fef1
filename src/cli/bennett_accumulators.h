#pragma once
// Bennett's accumulators as pictures (thesis 2.6.1, figs. 2.17-2.23), for
// `imagepro-cli detect --accumulators DIR`. Every path Bennett can take (at least
// max(min_path_pixels, 6) pixels) is accumulated in full, without the coarse screen, so
// the picture is the whole accumulator the decision rules read.
#include <opencv2/core.hpp>

#include <cstddef>
#include <vector>

#include "core/connectivity/paths.h"
#include "core/ellipse/detect.h"
#include "core/settings/options.h"

namespace imagepro::cli {

struct PathAccumulator {
  std::size_t path = 0;
  bool accepted = false;  // by Bennett's rules and the fit rule, as detect --method bennett decides
  BennettResult result;
  cv::Mat image;          // 8-bit BGR, enlarged, annotated
};

struct BennettAccumulators {
  // Image-sized, 8-bit grey: each path's accumulator over its box, scaled to its own
  // peak (255), the brighter one where boxes overlap (the thesis's one accumulation
  // space for the whole image, fig. 2.17, with every path's peak visible).
  cv::Mat all;
  // The paths Bennett accepts or, when it accepts none, the one of highest score (rule
  // 4): the accumulator in grey scaled to its peak, enlarged to about 320 px, the peak's
  // centre of symmetry marked in red, the circle of half the peak's mean score in blue
  // (fig. 2.22) and, when symmetry vanishes inside the box, that radius in orange.
  std::vector<PathAccumulator> shown;
};

void drawBennettAccumulators(const EllipseOptions& options, const Paths& paths, cv::Size image, EllipseWorkspace& ws,
                             BennettAccumulators& out);

}  // namespace imagepro::cli
