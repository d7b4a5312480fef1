#include "core/source/virtual_renderer.h"

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/common/lens_model.h"
#include "core/source/scene_shapes.h"

namespace imagepro {
namespace {

constexpr int kOutside = -1;  // a plane point beyond the card (target) or the sheet (pattern)

// What lies in the target plane (mm, target frame) and its grey levels.
struct PlaneScene {
  double disk_r2 = 0;
  double spot_r2 = 0;
  double spot_offset = 0;
  double card_half = 0;
  bool pattern = false;
  double sheet_hx = 0;
  double sheet_hy = 0;
  double spacing = 1;
  double grid_spot_r2 = 0;
  double columns = 1;
  double rows = 1;
  double col_centre = 0;  // (columns - 1) / 2: the grid is centred on the target
  double row_centre = 0;
  bool facing = true;  // the camera sees the printed side
  int white = 255;
  int black = 0;

  // Half extents of everything that is not background.
  double halfX() const { return pattern ? std::max(sheet_hx, card_half) : card_half; }
  double halfY() const { return pattern ? std::max(sheet_hy, card_half) : card_half; }

  // Level at the plane point (a / w, b / w), w > 0: homogeneous, so the target and
  // its card need no division.
  int levelAt(double a, double b, double w) const {
    const double cw = card_half * w;
    if (std::abs(a) <= cw && std::abs(b) <= cw) {
      if (!facing) return black;
      const double w2 = w * w;
      const double r2 = a * a + b * b;
      if (r2 > disk_r2 * w2 || r2 < spot_r2 * w2) return black;
      const double da = a - spot_offset * w;
      return da * da + b * b < spot_r2 * w2 ? black : white;
    }
    if (!pattern) return kOutside;
    return sheetLevel(a / w, b / w);
  }

  // Level at a plane point (x, y) beyond the card.
  int sheetLevel(double x, double y) const {
    const double ax = std::abs(x);
    const double ay = std::abs(y);
    if (ax > sheet_hx || ay > sheet_hy) return kOutside;
    if (!facing) return black;
    // Spots are smaller than half the spacing, so only the nearest grid node can hold x, y.
    // Clamped first, so truncating x + 0.5 rounds (and stays clear of libm calls).
    const double i = static_cast<int>(std::clamp(x / spacing + col_centre, 0.0, columns - 1.0) + 0.5);
    const double j = static_cast<int>(std::clamp(y / spacing + row_centre, 0.0, rows - 1.0) + 0.5);
    const double cx = (i - col_centre) * spacing;
    const double cy = (j - row_centre) * spacing;
    const double dx = x - cx;
    const double dy = y - cy;
    if (dx * dx + dy * dy >= grid_spot_r2) return white;
    // A grid spot that would touch the card is left out.
    const double gx = std::max(std::abs(cx) - card_half, 0.0);
    const double gy = std::max(std::abs(cy) - card_half, 0.0);
    return gx * gx + gy * gy <= grid_spot_r2 ? white : black;
  }
};

// Uniform in [0, 1) from the generator's raw bits (portable across standard libraries,
// unlike std::uniform_real_distribution).
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// White bars and rectangles (`level`), placed from `seed`, appended to `shapes`.
void appendClutter(int count, unsigned seed, int width, int height, int level, std::vector<SceneShape>& shapes) {
  std::mt19937_64 rng(0x9e3779b97f4a7c15ULL ^ seed);
  const double size = std::min(width, height);
  for (int k = 0; k < count; ++k) {
    SceneShape s;
    s.level = level;
    s.cu = uniform01(rng) * width - 0.5;
    s.cv = uniform01(rng) * height - 0.5;
    const double angle = uniform01(rng) * M_PI;
    s.du = std::cos(angle);
    s.dv = std::sin(angle);
    const double a = uniform01(rng);
    const double b = uniform01(rng);
    if (k % 2 == 0) {  // bar: long and thin
      s.half_len = 0.5 * size * (0.2 + 0.4 * a);
      s.half_wid = std::max(1.0, 0.5 * size * (0.008 + 0.025 * b));
    } else {  // rectangle
      s.half_len = 0.5 * size * (0.05 + 0.15 * a);
      s.half_wid = 0.5 * size * (0.05 + 0.15 * b);
    }
    s.setBox();
    shapes.push_back(s);
  }
}

// The renderer's undistortion: Newton's method (lens_model.h) to 1e-4 px, whose error is
// then of the order of the distortion's curvature times 1e-8 px^2.
constexpr int kUndistortIterations = 30;
constexpr double kUndistortStepPx = 1e-4;

bool undistortRelative(const Distortion& d, const Eigen::Vector2d& p, Eigen::Vector2d& q) {
  return invertDistortion(d, p, q, kUndistortIterations, kUndistortStepPx);
}

// As above from the best start available: `guess` if it converges, else p itself.
bool undistortFrom(const Distortion& d, const Eigen::Vector2d& p, const Eigen::Vector2d& guess, Eigen::Vector2d& q) {
  q = guess;
  if (undistortRelative(d, p, q)) return true;
  q = p;
  return undistortRelative(d, p, q);
}

// Per-camera data, kept between frames: the ray through every pixel centre (only
// with distortion) and the box of ideal pixel coordinates the image can see.
struct CameraCache {
  bool valid = false;
  int width = 0, height = 0;
  double fu = 0, fv = 0, u0 = 0, v0 = 0;
  Distortion distortion;
  cv::Mat rays;  // CV_64FC2: (X/Z, Y/Z) of the ray through each pixel centre, NaN if none
  bool invertible = true;  // every image point has an undistorted position
  double ideal_u_min = 0, ideal_u_max = 0, ideal_v_min = 0, ideal_v_max = 0;

  bool matches(const CameraModel& c) const {
    return valid && width == c.width && height == c.height && fu == c.fu() && fv == c.fv() && u0 == c.u0() &&
           v0 == c.v0() && distortion.k1 == c.distortion.k1 && distortion.k2 == c.distortion.k2 &&
           distortion.p1 == c.distortion.p1 && distortion.p2 == c.distortion.p2;
  }

  void update(const CameraModel& c) {
    if (matches(c)) return;
    width = c.width;
    height = c.height;
    fu = c.fu();
    fv = c.fv();
    u0 = c.u0();
    v0 = c.v0();
    distortion = c.distortion;
    const double margin = 2.0;
    invertible = true;
    if (distortion.isZero()) {
      rays.release();
      ideal_u_min = -0.5 - margin;
      ideal_u_max = width - 0.5 + margin;
      ideal_v_min = -0.5 - margin;
      ideal_v_max = height - 0.5 + margin;
    } else {
      rays.create(height, width, CV_64FC2);
      for (int v = 0; v < height; ++v) {
        auto* row = rays.ptr<cv::Vec2d>(v);
        Eigen::Vector2d q(-u0, v - v0);
        bool have_previous = false;
        for (int u = 0; u < width; ++u) {
          const Eigen::Vector2d p(u - u0, v - v0);
          const Eigen::Vector2d guess = have_previous ? Eigen::Vector2d(q.x() + 1.0, q.y()) : p;
          have_previous = undistortFrom(distortion, p, guess, q);
          if (have_previous) {
            row[u] = cv::Vec2d(q.x() / fu, q.y() / fv);
          } else {
            row[u] = cv::Vec2d(NAN, NAN);  // sees nothing: NaN fails every plane test
            invertible = false;
          }
        }
      }
      // The image border, undistorted, bounds what the image can see (the distortion
      // is a smooth one-to-one map over the image).
      ideal_u_min = ideal_v_min = INFINITY;
      ideal_u_max = ideal_v_max = -INFINITY;
      auto take = [&](double u, double v) {
        const Eigen::Vector2d p(u - u0, v - v0);
        Eigen::Vector2d q;
        if (!undistortFrom(distortion, p, p, q)) {
          invertible = false;
          return;
        }
        ideal_u_min = std::min(ideal_u_min, q.x() + u0);
        ideal_u_max = std::max(ideal_u_max, q.x() + u0);
        ideal_v_min = std::min(ideal_v_min, q.y() + v0);
        ideal_v_max = std::max(ideal_v_max, q.y() + v0);
      };
      const int n = 64;
      for (int k = 0; k <= n; ++k) {
        const double u = -0.5 + width * static_cast<double>(k) / n;
        const double v = -0.5 + height * static_cast<double>(k) / n;
        take(u, -0.5);
        take(u, height - 0.5);
        take(-0.5, v);
        take(width - 0.5, v);
      }
      ideal_u_min -= margin;
      ideal_u_max += margin;
      ideal_v_min -= margin;
      ideal_v_max += margin;
    }
    valid = true;
  }
};

// Everything reused from frame to frame by one thread.
struct Workspace {
  CameraCache camera;
  // The shapes behind the plane (the room, then the clutter over it) for the key below,
  // and their anti-aliased image, which stays the same from frame to frame.
  struct ShapesKey {
    Backdrop backdrop = Backdrop::Plain;
    int clutter = 0;
    unsigned seed = 0;
    int width = 0, height = 0, white = 0, background = 0;
    bool operator==(const ShapesKey&) const = default;
  };
  bool shapes_valid = false;
  ShapesKey shapes_key;
  std::vector<SceneShape> shapes;
  bool shapes_image_valid = false;
  int shapes_image_supersampling = 0;
  cv::Mat shapes_levels;  // CV_8UC1, pixel-centre levels of the shapes alone
  cv::Mat shapes_grey;    // CV_32FC1, the same anti-aliased
  cv::Mat room_light;     // CV_32FC1, Backdrop::Room's light (scene_shapes.h)
  cv::Mat levels;  // CV_8UC1, pixel-centre levels (grey mode)
  cv::Mat grey;    // CV_32FC1, anti-aliased image before conversion
  cv::Mat noise;   // CV_32FC1
  cv::Mat neighbour_max, neighbour_min;  // CV_8UC1, 3x3 extremes of `levels`

  // The room (grey mode only: the thesis's binary frames have none) and the clutter.
  const std::vector<SceneShape>& shapesFor(const VirtualSceneOptions& scene, bool binary, int width, int height,
                                           int white, int background) {
    const ShapesKey key{binary ? Backdrop::Plain : scene.backdrop, std::max(0, scene.clutter), scene.seed, width,
                        height, white, background};
    if (!shapes_valid || !(key == shapes_key)) {
      shapes.clear();
      if (key.backdrop == Backdrop::Room) {
        appendRoomBackdrop(key.seed, width, height, white, shapes);
        makeRoomLight(width, height, room_light);
      }
      appendClutter(key.clutter, key.seed, width, height, white, shapes);
      shapes_valid = true;
      shapes_key = key;
      shapes_image_valid = false;
    }
    return shapes;
  }
};

Workspace& workspace() {
  thread_local Workspace ws;
  return ws;
}

// The shapes that may cover some area of the image, in drawing order: a short list, or
// all of them when too many overlap there.
struct ClutterCandidates {
  static constexpr int kMax = 32;
  std::array<const SceneShape*, kMax> shapes;  // the first `count` are set
  int count = 0;
  bool all = false;
};

// One frame's rendering state: the camera, the plane's mapping and the scene.
class FrameRenderer {
 public:
  FrameRenderer(const CameraModel& cam, const CameraCache& cache, const PlaneScene& plane, const Pose& pose,
                const std::vector<SceneShape>& shapes, int background)
      : cam_(cam), cache_(cache), plane_(plane), clutter_(shapes), background_(background) {
    R_ = rotationMatrix(pose);
    T_ = translation(pose);
    // A camera ray d = (X/Z, Y/Z, 1) meets the plane at lambda * d = x r1 + y r2 + T, so
    // (x, y, 1) / lambda = M^-1 d with M = [r1 r2 T]; lambda > 0 means in front.
    const double distance = R_.col(2).dot(T_);  // signed distance of the camera from the plane
    plane_.facing = distance > 0.0;
    visible_ = std::abs(distance) > 1e-9 * std::max(1.0, T_.norm());  // not edge-on
    if (visible_) {
      Eigen::Matrix3d M;
      M << R_.col(0), R_.col(1), T_;
      G_ = M.inverse();
    }
    distorted_ = !cache_.rays.empty();
    roi_ = computeRoi();
  }

  // Pixels outside this rectangle see no part of the plane scene.
  const cv::Rect& roi() const { return roi_; }

  // Level at a sample point (u, v) of the image whose camera ray is (xn, yn, 1);
  // `clutter` holds the shapes that may contain it.
  int levelOfRay(double xn, double yn, double u, double v, const ClutterCandidates& clutter) const {
    if (visible_) {
      const double w = G_(2, 0) * xn + G_(2, 1) * yn + G_(2, 2);
      if (w > 0.0) {
        const double a = G_(0, 0) * xn + G_(0, 1) * yn + G_(0, 2);
        const double b = G_(1, 0) * xn + G_(1, 1) * yn + G_(1, 2);
        const int level = plane_.levelAt(a, b, w);
        if (level != kOutside) return level;
      }
    }
    return clutterOrBackground(u, v, clutter);
  }

  // Level behind the plane scene at (u, v): the topmost shape there (the last drawn), or
  // the background.
  int clutterOrBackground(double u, double v, const ClutterCandidates& clutter) const {
    if (clutter.all) {
      for (auto s = clutter_.rbegin(); s != clutter_.rend(); ++s)
        if (s->contains(u, v)) return s->level;
    } else {
      for (int k = clutter.count - 1; k >= 0; --k)
        if (clutter.shapes[k]->contains(u, v)) return clutter.shapes[k]->level;
    }
    return background_;
  }

  // Ray through the pixel centre (u, v).
  void pixelRay(int u, int v, double& xn, double& yn) const {
    if (!distorted_) {
      xn = (u - cache_.u0) / cache_.fu;
      yn = (v - cache_.v0) / cache_.fv;
    } else {
      const cv::Vec2d& r = cache_.rays.ptr<cv::Vec2d>(v)[u];
      xn = r[0];
      yn = r[1];
    }
  }

  // Fills `out` (CV_8UC1) with the pixel-centre levels of the shapes and the background
  // alone, as if no plane were there.
  void renderShapeCentres(cv::Mat& out) const {
    out.setTo(cv::Scalar(background_));
    const cv::Rect image(0, 0, out.cols, out.rows);
    for (const auto& s : clutter_) {
      const cv::Rect box = cv::Rect(s.u_min, s.v_min, s.u_max - s.u_min + 1, s.v_max - s.v_min + 1) & image;
      for (int v = box.y; v < box.y + box.height; ++v) {
        auto* row = out.ptr<std::uint8_t>(v);
        for (int u = box.x; u < box.x + box.width; ++u)
          if (s.contains(u, v)) row[u] = static_cast<std::uint8_t>(s.level);
      }
    }
  }

  // Mean level of the shapes and background alone over the pixel's area, n x n samples.
  float shapesAverage(int u, int v, int n) const {
    const ClutterCandidates near = candidates(cv::Rect(u, v, 1, 1));
    int sum = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) sum += clutterOrBackground(u + (i + 0.5) / n - 0.5, v + (j + 0.5) / n - 0.5, near);
    return static_cast<float>(sum) / static_cast<float>(n * n);
  }

  // Fills `out` (CV_8UC1) with pixel-centre levels.
  void renderCentres(cv::Mat& out) const {
    renderShapeCentres(out);
    renderPlaneCentres(out);
  }

  // Overwrites the pixel centres of the rectangle that may see the plane scene.
  void renderPlaneCentres(cv::Mat& out) const {
    if (roi_.empty()) return;
    const ClutterCandidates near = candidates(roi_);
    // Local copies: byte stores into `out` may alias anything, so members would be
    // reloaded for every pixel.
    const PlaneScene plane = plane_;
    const bool visible = visible_;
    const double g00 = G_(0, 0), g01 = G_(0, 1), g02 = G_(0, 2);
    const double g10 = G_(1, 0), g11 = G_(1, 1), g12 = G_(1, 2);
    const double g20 = G_(2, 0), g21 = G_(2, 1), g22 = G_(2, 2);
    const double inv_fu = 1.0 / cache_.fu;
    const double inv_fv = 1.0 / cache_.fv;
    const double u0 = cache_.u0;
    const double v0 = cache_.v0;
    auto level = [&](double xn, double yn, int u, int v) {
      if (visible) {
        const double w = g20 * xn + g21 * yn + g22;
        if (w > 0.0) {
          const int l = plane.levelAt(g00 * xn + g01 * yn + g02, g10 * xn + g11 * yn + g12, w);
          if (l != kOutside) return l;
        }
      }
      return clutterOrBackground(u, v, near);
    };
    for (int v = roi_.y; v < roi_.y + roi_.height; ++v) {
      auto* row = out.ptr<std::uint8_t>(v);
      if (distorted_) {
        const auto* rays = cache_.rays.ptr<cv::Vec2d>(v);
        for (int u = roi_.x; u < roi_.x + roi_.width; ++u)
          row[u] = static_cast<std::uint8_t>(level(rays[u][0], rays[u][1], u, v));
      } else {
        const double yn = (v - v0) * inv_fv;
        for (int u = roi_.x; u < roi_.x + roi_.width; ++u)
          row[u] = static_cast<std::uint8_t>(level((u - u0) * inv_fu, yn, u, v));
      }
    }
  }

  // Mean level over the pixel's area, n x n samples.
  float pixelAverage(int u, int v, int n) const {
    const ClutterCandidates near = candidates(cv::Rect(u, v, 1, 1));
    double cxn, cyn;
    pixelRay(u, v, cxn, cyn);
    // The undistortion is linearised about the pixel centre for a start close enough
    // that Newton's method converges in about one step.
    double i00 = 1, i01 = 0, i11 = 1, qu = 0, qv = 0;
    if (distorted_ && !std::isfinite(cxn)) {
      // The centre lies beyond the fold of the model: start each sample from itself.
      qu = u - cache_.u0;
      qv = v - cache_.v0;
    } else if (distorted_) {
      qu = cxn * cache_.fu;
      qv = cyn * cache_.fv;
      const Eigen::Matrix2d inverse =
          (Eigen::Matrix2d::Identity() + distortionWithJacobian(cache_.distortion, {qu, qv}).J).inverse();
      i00 = inverse(0, 0);
      i01 = inverse(0, 1);
      i11 = inverse(1, 1);
    }
    int sum = 0;
    for (int j = 0; j < n; ++j) {
      const double dv = (j + 0.5) / n - 0.5;
      for (int i = 0; i < n; ++i) {
        const double du = (i + 0.5) / n - 0.5;
        double xn, yn;
        if (!distorted_) {
          xn = cxn + du / cache_.fu;
          yn = cyn + dv / cache_.fv;
        } else {
          const Eigen::Vector2d p(u + du - cache_.u0, v + dv - cache_.v0);
          Eigen::Vector2d q(qu + i00 * du + i01 * dv, qv + i01 * du + i11 * dv);
          if (!undistortRelative(cache_.distortion, p, q)) {
            sum += clutterOrBackground(u + du, v + dv, near);
            continue;
          }
          xn = q.x() / cache_.fu;
          yn = q.y() / cache_.fv;
        }
        sum += levelOfRay(xn, yn, u + du, v + dv, near);
      }
    }
    return static_cast<float>(sum) / static_cast<float>(n * n);
  }

 private:
  // The image rectangle that can see the plane scene: its extent projected with the
  // distortion, padded so that every pixel whose area touches it is inside.
  cv::Rect computeRoi() const {
    const cv::Rect image(0, 0, cam_.width, cam_.height);
    if (!visible_) return {};
    // Beyond the fold of an extreme distortion model the box below cannot be trusted.
    if (!cache_.invertible) return image;
    const double hx = plane_.halfX();
    const double hy = plane_.halfY();
    double iu_min = INFINITY, iu_max = -INFINITY, iv_min = INFINITY, iv_max = -INFINITY;
    for (int sx = -1; sx <= 1; sx += 2) {
      for (int sy = -1; sy <= 1; sy += 2) {
        const Eigen::Vector3d P = R_ * Eigen::Vector3d(sx * hx, sy * hy, 0.0) + T_;
        if (P.z() <= 1e-9) return image;  // part of it reaches behind the camera: unbounded
        const Eigen::Vector2d q = projectIdeal(cam_, P);
        iu_min = std::min(iu_min, q.x());
        iu_max = std::max(iu_max, q.x());
        iv_min = std::min(iv_min, q.y());
        iv_max = std::max(iv_max, q.y());
      }
    }
    iu_min = std::max(iu_min, cache_.ideal_u_min);
    iu_max = std::min(iu_max, cache_.ideal_u_max);
    iv_min = std::max(iv_min, cache_.ideal_v_min);
    iv_max = std::min(iv_max, cache_.ideal_v_max);
    if (iu_min > iu_max || iv_min > iv_max) return {};
    double u_min = iu_min, u_max = iu_max, v_min = iv_min, v_max = iv_max;
    if (!cam_.distortion.isZero()) {
      // The distorted image of the ideal box is bounded by the image of its border.
      u_min = v_min = INFINITY;
      u_max = v_max = -INFINITY;
      const int n = 32;
      auto take = [&](double u, double v) {
        const Eigen::Vector2d d = distortPixel(cam_, Eigen::Vector2d(u, v));
        u_min = std::min(u_min, d.x());
        u_max = std::max(u_max, d.x());
        v_min = std::min(v_min, d.y());
        v_max = std::max(v_max, d.y());
      };
      for (int k = 0; k <= n; ++k) {
        const double u = iu_min + (iu_max - iu_min) * k / n;
        const double v = iv_min + (iv_max - iv_min) * k / n;
        take(u, iv_min);
        take(u, iv_max);
        take(iu_min, v);
        take(iu_max, v);
      }
    }
    const double pad = 2.0;
    const double lo_u = std::max(std::floor(u_min - pad), -1.0);
    const double hi_u = std::min(std::ceil(u_max + pad), static_cast<double>(cam_.width));
    const double lo_v = std::max(std::floor(v_min - pad), -1.0);
    const double hi_v = std::min(std::ceil(v_max + pad), static_cast<double>(cam_.height));
    if (lo_u > hi_u || lo_v > hi_v) return {};
    const cv::Rect box(static_cast<int>(lo_u), static_cast<int>(lo_v), static_cast<int>(hi_u - lo_u) + 1,
                       static_cast<int>(hi_v - lo_v) + 1);
    return box & image;
  }

  const CameraModel& cam_;
  const CameraCache& cache_;
  PlaneScene plane_;
  const std::vector<SceneShape>& clutter_;  // the room and clutter, in drawing order
  int background_;
  Eigen::Matrix3d R_;
  Eigen::Vector3d T_;
  Eigen::Matrix3d G_ = Eigen::Matrix3d::Zero();
  bool visible_ = false;
  bool distorted_ = false;
  cv::Rect roi_;

  // The shapes whose (padded) box meets `area`.
  ClutterCandidates candidates(const cv::Rect& area) const {
    ClutterCandidates c;
    for (const auto& s : clutter_) {
      if (s.u_max < area.x || s.u_min >= area.x + area.width || s.v_max < area.y || s.v_min >= area.y + area.height)
        continue;
      if (c.count == ClutterCandidates::kMax) {
        c.all = true;
        break;
      }
      c.shapes[c.count++] = &s;
    }
    return c;
  }
};

int clampLevel(int level) { return std::clamp(level, 0, 255); }

void render(const CameraModel& cam, PlaneScene plane, const VirtualSceneOptions& scene, const Pose& pose,
            cv::Mat& out, std::uint64_t frame_seed) {
  const int width = std::max(cam.width, 0);
  const int height = std::max(cam.height, 0);
  out.create(height, width, CV_8UC1);
  if (width == 0 || height == 0) return;

  Workspace& ws = workspace();
  ws.camera.update(cam);
  const bool binary = scene.mode == RenderMode::Binary;
  plane.white = binary ? 255 : clampLevel(scene.white_level);
  plane.black = binary ? 0 : clampLevel(scene.black_level);
  const int background = binary ? 0 : clampLevel(scene.background_level);
  const auto& shapes = ws.shapesFor(scene, binary, width, height, plane.white, background);
  // When the card looks like the background, only the disk needs the full test.
  if (!plane.pattern && shapes.empty() && plane.black == background)
    plane.card_half = std::sqrt(plane.disk_r2);

  const FrameRenderer renderer(cam, ws.camera, plane, pose, shapes, background);
  if (binary) {
    renderer.renderCentres(out);
    return;
  }

  // Grey: pixel-centre levels, then anti-aliasing where a pixel differs from a neighbour
  // (a straight edge crossing a pixel always separates two of the 3x3 centres around it).
  // The shapes behind the plane do not move: their image is made once, and each frame
  // draws only the rectangle that may see the plane over it.
  const int n = std::max(1, scene.supersampling);
  cv::Mat& levels = ws.levels;
  cv::Mat& grey = ws.grey;
  levels.create(height, width, CV_8UC1);
  const auto antialias = [&](const cv::Rect& area, auto&& average) {
    if (area.empty()) return;
    const cv::Rect scan = cv::Rect(area.x - 1, area.y - 1, area.width + 2, area.height + 2) & cv::Rect(0, 0, width, height);
    const cv::Mat part = levels(scan);
    cv::dilate(part, ws.neighbour_max, cv::Mat());
    cv::erode(part, ws.neighbour_min, cv::Mat());
    for (int y = 0; y < scan.height; ++y) {
      const auto* hi = ws.neighbour_max.ptr<std::uint8_t>(y);
      const auto* lo = ws.neighbour_min.ptr<std::uint8_t>(y);
      auto* grey_row = grey.ptr<float>(scan.y + y) + scan.x;
      for (int x = 0; x < scan.width; ++x)
        if (hi[x] != lo[x]) grey_row[x] = average(scan.x + x, scan.y + y);
    }
  };
  if (shapes.empty()) {
    renderer.renderCentres(levels);
    levels.convertTo(grey, CV_32F);
  } else {
    if (!ws.shapes_image_valid || ws.shapes_image_supersampling != n) {
      renderer.renderShapeCentres(levels);
      levels.convertTo(grey, CV_32F);
      antialias(cv::Rect(0, 0, width, height), [&](int u, int v) { return renderer.shapesAverage(u, v, n); });
      levels.copyTo(ws.shapes_levels);
      grey.copyTo(ws.shapes_grey);
      ws.shapes_image_valid = true;
      ws.shapes_image_supersampling = n;
    }
    ws.shapes_levels.copyTo(levels);
    ws.shapes_grey.copyTo(grey);
    renderer.renderPlaneCentres(levels);
    if (!renderer.roi().empty()) levels(renderer.roi()).convertTo(grey(renderer.roi()), CV_32F);
  }
  antialias(renderer.roi(), [&](int u, int v) { return renderer.pixelAverage(u, v, n); });

  if (ws.shapes_key.backdrop == Backdrop::Room) cv::multiply(grey, ws.room_light, grey);
  if (scene.illumination_gradient != 0.0) {
    const double g = scene.illumination_gradient;
    const double span = std::max(width - 1, 1);
    for (int v = 0; v < height; ++v) {
      auto* row = grey.ptr<float>(v);
      for (int u = 0; u < width; ++u) row[u] *= static_cast<float>(1.0 + g * (u / span - 0.5));
    }
  }
  if (scene.blur_sigma_px > 0.0)
    cv::GaussianBlur(grey, grey, cv::Size(0, 0), scene.blur_sigma_px, scene.blur_sigma_px, cv::BORDER_REPLICATE);
  if (scene.noise_sigma > 0.0) {
    // The same scene seed and frame seed give the same noise.
    const std::uint64_t state =
        (0x2545f4914f6cdd1dULL * (frame_seed + 1)) ^ ((static_cast<std::uint64_t>(scene.seed) << 32) | 0x5bd1e995u);
    cv::RNG rng(state);
    ws.noise.create(height, width, CV_32FC1);
    rng.fill(ws.noise, cv::RNG::NORMAL, 0.0, scene.noise_sigma);
    grey += ws.noise;
  }
  grey.convertTo(out, CV_8U);  // rounds and saturates to 0..255
}

PlaneScene targetPlane(const TargetGeometry& target, double card_size_mm) {
  PlaneScene p;
  p.disk_r2 = target.radius_mm * target.radius_mm;
  p.spot_r2 = target.spot_radius_mm * target.spot_radius_mm;
  p.spot_offset = target.spot_offset_mm;
  // The card carries the whole disk, whatever size it is given.
  p.card_half = std::max(0.5 * card_size_mm, target.radius_mm);
  return p;
}

}  // namespace

void renderTarget(const CameraModel& camera, const TargetGeometry& target, const VirtualSceneOptions& scene,
                  const Pose& pose, cv::Mat& out, std::uint64_t frame_seed) {
  render(camera, targetPlane(target, scene.card_size_mm), scene, pose, out, frame_seed);
}

void renderPattern(const CameraModel& camera, const TargetGeometry& target, const PatternGeometry& pattern,
                   const VirtualSceneOptions& scene, const Pose& pose, cv::Mat& out, std::uint64_t frame_seed) {
  PlaneScene p = targetPlane(target, pattern.card_size_mm);
  p.pattern = true;
  p.spacing = std::max(pattern.spot_spacing_mm, 1e-9);
  // Spots reaching half the spacing would merge; the nearest-node test assumes they do not.
  const double spot_r = std::min(pattern.spot_radius_mm, 0.5 * p.spacing);
  p.grid_spot_r2 = spot_r * spot_r;
  p.columns = std::max(pattern.columns, 1);
  p.rows = std::max(pattern.rows, 1);
  p.col_centre = 0.5 * (p.columns - 1.0);
  p.row_centre = 0.5 * (p.rows - 1.0);
  p.sheet_hx = 0.5 * p.columns * p.spacing;
  p.sheet_hy = 0.5 * p.rows * p.spacing;
  // A calibration measures the lens: the sheet lies on the plain background, evenly lit.
  VirtualSceneOptions plain = scene;
  plain.backdrop = Backdrop::Plain;
  render(camera, p, plain, pose, out, frame_seed);
}

bool targetInView(const CameraModel& camera, const TargetGeometry& target, const Pose& pose) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  if (!(R.col(2).dot(T) > 1e-9 * T.norm())) return false;  // edge-on or facing away
  for (int k = 0; k < 360; ++k) {
    const double a = k * M_PI / 180.0;
    const Eigen::Vector3d P = R * Eigen::Vector3d(target.radius_mm * std::cos(a), target.radius_mm * std::sin(a), 0) + T;
    if (!(P.z() > 0.0)) return false;
    const Eigen::Vector2d p = distortPixel(camera, projectIdeal(camera, P));
    if (!(p.x() >= 0.0 && p.y() >= 0.0 && p.x() <= camera.width - 1.0 && p.y() <= camera.height - 1.0)) return false;
  }
  return true;
}

}  // namespace imagepro
