#pragma once
// The flat shapes the virtual renderer draws behind the target plane, fixed in the image
// (distorted pixel coordinates): the clutter's white bars and rectangles, and the room
// backdrop (VirtualSceneOptions::backdrop) of a wall, a desk and what stands on it.
#include <opencv2/core.hpp>

#include <vector>

namespace imagepro {

// A rectangle of one grey level, turned by its unit direction (du, dv).
struct SceneShape {
  double cu = 0, cv = 0;  // centre
  double du = 1, dv = 0;  // unit direction of the long side
  double half_len = 0, half_wid = 0;
  int level = 0;
  int u_min = 0, u_max = -1, v_min = 0, v_max = -1;  // pixel bounding box (unclipped); setBox()

  bool contains(double u, double v) const {
    const double pu = u - cu;
    const double pv = v - cv;
    return std::abs(pu * du + pv * dv) <= half_len && std::abs(pv * du - pu * dv) <= half_wid;
  }
  void setBox();
};

// The room for a width x height image, the bottom shape first (later shapes cover
// earlier ones); `white` is the paper's level, which the room's levels follow. `seed`
// moves things a little, so that two seeds give two rooms.
void appendRoomBackdrop(unsigned seed, int width, int height, int white, std::vector<SceneShape>& shapes);

// The room's light, a factor per pixel (CV_32FC1) that the frame is multiplied by: more
// from the window on the left, less towards the corners (the lens's vignetting), 1 at the
// image centre.
void makeRoomLight(int width, int height, cv::Mat& light);

}  // namespace imagepro
