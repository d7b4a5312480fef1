#pragma once
// Connectivity analysis (thesis 2.5): groups the edge pixels into 8-connected paths,
// the borders of separate regions, for the ellipse detection. Every edge pixel ends
// up in exactly one path and a path has no length limit.
//
//  - CN0: the earlier study's grouping with its bugs and path limit removed. For each
//    pixel of a growing path it scans every pixel not yet assigned: O(n^2).
//  - CN1 (2.5.1): one pass, O(n). Starting from an unassigned pixel, the neighbours of
//    each pixel of the path are moved to just after the path's current end of the
//    reordered list; neighbours are found in O(1) through an index image.
//
// Canonical output (both methods give identical `Paths`, pixel for pixel): paths in
// the order of their earliest pixel in the input list (for the raster-ordered lists
// of detectEdges: by their first pixel in raster order); each path starts with that
// pixel and continues breadth first, the new neighbours of a pixel appended in
// raster order (row, then column).
#include <opencv2/core.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/common/status.h"
#include "core/connectivity/paths.h"
#include "core/edges/edge_list.h"
#include "core/settings/options.h"

namespace imagepro {

// Buffers reused from frame to frame.
struct ConnectivityWorkspace {
  // (height + 2) x (width + 3), CV_32SC1: the list index of the edge pixel at
  // (x, y) is at (y + 1, x + 1), -1 elsewhere (a frame, and a spare last column). Every
  // entry is -1 between calls, so a frame only touches the entries of its own edge pixels.
  cv::Mat index;
  // CN1: the index-image offset of the first fresh neighbour for each 8-bit neighbour
  // mask (built with the index image, as it depends on its row length).
  std::array<std::ptrdiff_t, 256> first_neighbour{};
  std::vector<std::int32_t*> queue;       // CN1: index-image entry of each pixel, in path order
  std::vector<std::uint8_t> joined;       // CN1: 1 once a list entry is in a path; 8 more past the list, the first 0
  std::vector<std::uint32_t> unassigned;  // CN0: input indices not yet in a path, in input order
};

// Each returns EmptyFrame for a non-positive image size, NoEdges (with `out` empty)
// for an empty list, InvalidEdgeList when a pixel lies outside the image or appears
// twice (`out` empty), Ok otherwise. `out` is cleared first and its capacity reused.
Status connectCN0(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws);
Status connectCN1(const EdgeList& edges, cv::Size imageSize, Paths& out, ConnectivityWorkspace& ws);
Status connectPaths(ConnectivityMethod method, const EdgeList& edges, cv::Size imageSize, Paths& out,
                    ConnectivityWorkspace& ws);

}  // namespace imagepro
