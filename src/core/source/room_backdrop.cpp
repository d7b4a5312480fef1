#include "core/source/scene_shapes.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace imagepro {

void SceneShape::setBox() {
  const double eu = std::abs(du) * half_len + std::abs(dv) * half_wid;
  const double ev = std::abs(dv) * half_len + std::abs(du) * half_wid;
  u_min = static_cast<int>(std::floor(cu - eu)) - 1;
  u_max = static_cast<int>(std::ceil(cu + eu)) + 1;
  v_min = static_cast<int>(std::floor(cv - ev)) - 1;
  v_max = static_cast<int>(std::ceil(cv + ev)) + 1;
}

namespace {

// Lays out shapes in fractions of the image, with levels as fractions of the paper's white.
class RoomBuilder {
 public:
  RoomBuilder(unsigned seed, int width, int height, int white, std::vector<SceneShape>& shapes)
      : rng_(0x51ed270b27e5a3c1ULL ^ seed), w_(width), h_(height), white_(white), shapes_(shapes) {}

  // A little movement, +-`fraction` of the image's size.
  double jitter(double fraction) { return fraction * (2.0 * static_cast<double>(rng_() >> 11) * 0x1.0p-53 - 1.0); }

  // An upright box from (x0, y0) to (x1, y1), in fractions of the width and height.
  void box(double x0, double y0, double x1, double y1, double level) { turned(x0, y0, x1, y1, 0.0, level); }

  // The same box turned by `degrees` about its centre.
  void turned(double x0, double y0, double x1, double y1, double degrees, double level) {
    SceneShape s;
    s.cu = 0.5 * (x0 + x1) * w_ - 0.5;
    s.cv = 0.5 * (y0 + y1) * h_ - 0.5;
    const double a = degrees * M_PI / 180.0;
    s.du = std::cos(a);
    s.dv = std::sin(a);
    s.half_len = std::max(0.5, 0.5 * std::abs(x1 - x0) * w_);
    s.half_wid = std::max(0.5, 0.5 * std::abs(y1 - y0) * h_);
    s.level = std::clamp(static_cast<int>(std::lround(level * white_)), 0, 255);
    s.setBox();
    shapes_.push_back(s);
  }

 private:
  std::mt19937_64 rng_;
  double w_, h_;
  int white_;
  std::vector<SceneShape>& shapes_;
};

}  // namespace

void appendRoomBackdrop(unsigned seed, int width, int height, int white, std::vector<SceneShape>& shapes) {
  if (width <= 0 || height <= 0) return;
  RoomBuilder room(seed, width, height, white, shapes);
  const double desk = 0.64 + room.jitter(0.03);  // where the wall meets the desk
  room.box(-0.01, -0.01, 1.01, desk, 0.62);      // the wall
  // A window on the left: the bright panes, their frame, and the sill.
  const double wx = 0.04 + room.jitter(0.02), wy = 0.05 + room.jitter(0.02);
  room.box(wx, wy, wx + 0.26, wy + 0.36, 0.97);
  room.box(wx + 0.124, wy, wx + 0.136, wy + 0.36, 0.45);
  room.box(wx, wy + 0.17, wx + 0.26, wy + 0.185, 0.45);
  room.box(wx - 0.012, wy + 0.36, wx + 0.272, wy + 0.38, 0.75);
  // A picture on the right of the wall.
  const double px = 0.60 + room.jitter(0.03);
  room.box(px, 0.07, px + 0.14, 0.24, 0.82);
  room.box(px + 0.015, 0.09, px + 0.125, 0.22, 0.34);
  room.box(px + 0.015, 0.16, px + 0.125, 0.22, 0.22);  // its dark hills
  // The desk, its front edge catching the light, the grain of its boards.
  room.box(-0.01, desk, 1.01, 1.01, 0.40);
  room.box(-0.01, desk, 1.01, desk + 0.012, 0.56);
  for (double y : {0.76, 0.87, 0.95}) room.turned(-0.05, y - 0.003, 1.05, y + 0.003, room.jitter(0.6), 0.35);
  // Books upright on the left end of the desk, the last one leaning.
  const double book_levels[] = {0.20, 0.74, 0.38, 0.86, 0.27, 0.55};
  double bx = 0.02 + room.jitter(0.01);
  for (int k = 0; k < 6; ++k) {
    const double width_k = 0.026 + 0.012 * ((k * 7) % 3) + room.jitter(0.004);
    const double tall = 0.17 + 0.035 * ((k * 5) % 4) + room.jitter(0.01);
    if (k < 5) room.box(bx, desk - tall, bx + width_k, desk + 0.005, book_levels[k]);
    else room.turned(bx + 0.01, desk - tall + 0.01, bx + 0.01 + width_k, desk + 0.002, -14.0, book_levels[k]);
    bx += width_k + 0.003;
  }
  // A monitor on the right: the stand, the bezel, the screen with a window on it.
  const double mx = 0.70 + room.jitter(0.02);
  room.box(mx + 0.11, 0.56, mx + 0.14, desk + 0.02, 0.16);
  room.box(mx + 0.06, desk + 0.005, mx + 0.19, desk + 0.03, 0.16);
  room.box(mx, 0.22, mx + 0.26, 0.57, 0.10);
  room.box(mx + 0.012, 0.235, mx + 0.248, 0.545, 0.26);
  room.box(mx + 0.03, 0.26, mx + 0.16, 0.40, 0.62);
  room.box(mx + 0.03, 0.26, mx + 0.16, 0.28, 0.45);
  // A keyboard in front of it, its rows of keys.
  room.turned(0.52, 0.78, 0.80, 0.84, -2.0, 0.22);
  for (double y : {0.795, 0.81, 0.825}) room.turned(0.53, y - 0.004, 0.79, y + 0.004, -2.0, 0.30);
  // A mug and its handle, a cable across the desk.
  const double gx = 0.40 + room.jitter(0.03);
  room.box(gx, desk + 0.04, gx + 0.05, desk + 0.14, 0.88);
  room.box(gx + 0.05, desk + 0.065, gx + 0.065, desk + 0.11, 0.80);
  room.box(gx, desk + 0.04, gx + 0.05, desk + 0.05, 0.60);
  room.turned(0.05, 0.90, 1.05, 0.906, 6.0 + room.jitter(2.0), 0.08);
}

void makeRoomLight(int width, int height, cv::Mat& light) {
  light.create(std::max(height, 0), std::max(width, 0), CV_32FC1);
  const double cu = 0.5 * (width - 1), cv = 0.5 * (height - 1);
  const double ru = std::max(cu, 1.0), rv = std::max(cv, 1.0);
  for (int v = 0; v < height; ++v) {
    auto* row = light.ptr<float>(v);
    const double y = (v - cv) / rv;
    for (int u = 0; u < width; ++u) {
      const double x = (u - cu) / ru;
      const double window = 1.0 - 0.10 * x;                    // brighter on the window's side
      const double vignetting = 1.0 - 0.13 * (x * x + y * y);  // 0.74 in the corners
      row[u] = static_cast<float>(window * vignetting);
    }
  }
}

}  // namespace imagepro
