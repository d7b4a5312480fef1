#pragma once
// Edge detection on the binary image (thesis 2.4). Input: CV_8UC1, 0 = black,
// nonzero = white. Output: the edge pixels in raster order (row by row, left to
// right), each with the Sobel gradient of the 0/1 image (eqs. 2.18-2.20): gx to the
// right (+u), gy downwards (+v), so the gradient points from black towards white.
//
// Pixels outside the image take the value of the nearest image pixel (replicated
// border), so they are never black: the image border itself is never an edge and a
// region cut by the border has an open contour (thesis fig. 2.27).
//
//  - Laplace (2.4.3, eq. 2.25): a white pixel with at least one black 4-neighbour.
//    One pixel thick, 8-connected around every region, and a one-pixel-wide line is
//    its own edge. Gradients are computed at the edge pixels only.
//  - Sobel + thinning (2.4.1-2.4.2, eq. 2.21, the older method kept for comparison):
//    every pixel with a non-zero Sobel gradient (both sides of each boundary), then
//    the three-pixel thinning: while three edge pixels are pairwise 8-neighbours, one
//    of them is deleted, a black one when there is one. The result has no such triple
//    and straight boundaries end up on their white side, but, as the thesis notes,
//    corners are cut, small spots deformed and some isolated points remain.
#include <opencv2/core.hpp>

#include "core/common/status.h"
#include "core/edges/edge_list.h"
#include "core/settings/options.h"

namespace imagepro {

// Buffers reused from frame to frame by the Sobel + thinning method.
struct EdgeWorkspace {
  cv::Mat gx, gy;  // CV_16SC1 Sobel responses of the whole 0/1 image
  cv::Mat mask;    // CV_8UC1 edge mask (1 = edge) during thinning, one-pixel zero frame
};

// Each returns EmptyFrame for an empty, non-CV_8UC1 or over-large (> 32767 px) image,
// NoEdges (with `out` empty) when no pixel is an edge, Ok otherwise. `out` is cleared
// first and its capacity reused.
Status detectEdgesLaplace(const cv::Mat& binary, EdgeList& out);
Status detectEdgesSobelThinning(const cv::Mat& binary, EdgeList& out, EdgeWorkspace& ws);
Status detectEdges(EdgeMethod method, const cv::Mat& binary, EdgeList& out, EdgeWorkspace& ws);

}  // namespace imagepro
