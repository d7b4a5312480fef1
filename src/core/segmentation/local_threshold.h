#pragma once
// Local (adaptive) binarization, beyond the thesis's one threshold per frame: each pixel
// is compared with the mean grey level of the window around it, so a white disk on its
// dark card stays white where the frame is dim and a bright window or lit wall elsewhere
// does not pull the threshold above it (uneven light, issue of real scenes).
//
// A pixel is black (0) when it is darker than its window's mean m (not rounded) by more
// than max(offset * m, min_contrast) grey levels, white (255) otherwise. The relative part
// follows the light (a shadow scales grey levels); the absolute part keeps flat dark
// areas, where noise swings about a low mean, white instead of speckled. So the black
// pixels are those clearly darker than their neighbourhood: the card around the disk,
// the spots inside it; a uniform area of any brightness is white.
#include <opencv2/core.hpp>

#include <cstdint>
#include <vector>

#include "core/settings/options.h"

namespace imagepro {

// The window's side in pixels for an image of `size`: options.window_px when set, else
// a sixteenth of the image's width (41 px at 640 x 480: wider than any blur, and about a
// near target's spot), at least 15; always odd.
int localWindowPx(const BinarizationOptions& options, cv::Size size);

// Buffers reused from frame to frame (no heap allocation once grown).
struct LocalThresholdWorkspace {
  std::vector<std::uint32_t> column_sums;  // per column: the sum over the window's rows
  std::vector<std::uint32_t> row_prefix;   // prefix sums of column_sums along the row
};

// `binary` as described above, CV_8UC1 of grey's size, keeping its allocation from call
// to call like binarize() (threshold.h). An empty or non-CV_8UC1 `grey` gives an empty
// `binary`. `binary` must not share grey's allocation.
void binarizeLocal(const cv::Mat& grey, const BinarizationOptions& options, LocalThresholdWorkspace& ws,
                   cv::Mat& binary);

}  // namespace imagepro
