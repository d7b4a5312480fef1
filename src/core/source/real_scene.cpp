#include "core/source/real_scene.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "core/source/virtual_renderer.h"

namespace imagepro {

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kFrameMarginPx = 2.0;

// Everything a still draws from its seed, in separate streams so that a rejected draw
// in one does not shift the others.
struct StillDraw {
  std::size_t photo = 0;
  double zoom = 1, fx = 0.5, fy = 0.5;
  Pose pose;
  TargetLook look;
  SceneConditions conditions;
  RigDraw rig;
};

Pose randomStillPose(const Settings& s, SceneRandom& random) {
  const CameraModel& cam = s.camera();
  const double card = s.virtual_scene.card_size_mm;
  const double distance = random.uniform(RealScenes::kMinDistanceMm, RealScenes::kMaxDistanceMm);
  const double tilt = random.uniform(0.0, RealScenes::kMaxTiltDeg);
  const double azimuth = random.uniform(0.0, 360.0);
  const double inplane = random.uniform(-180.0, 180.0);
  // The distance and tilt are kept and the place in the frame redrawn, so near targets
  // are not thinned out; the principal point holds every card the range allows.
  for (int attempt = 0; attempt < 64; ++attempt) {
    const Eigen::Vector2d centre(random.uniform(0.0, cam.width - 1.0), random.uniform(0.0, cam.height - 1.0));
    const Pose pose = poseAlongRay(cam, centre, distance, tilt, azimuth, inplane);
    if (cardInFrame(cam, s.target, card, pose, kFrameMarginPx)) return pose;
  }
  return poseAlongRay(cam, Eigen::Vector2d(cam.u0(), cam.v0()), distance, tilt, azimuth, inplane);
}

StillDraw drawStill(const Settings& s, const RigEffects& rig, std::size_t photos, std::uint64_t seed,
                    std::int64_t index) {
  const std::uint64_t base = mixSeed(seed, static_cast<std::uint64_t>(index));
  StillDraw d;
  SceneRandom scene(mixSeed(base, 0));
  d.photo = photos ? static_cast<std::size_t>(scene.bits() % photos) : 0;
  d.zoom = scene.uniform(1.0, 1.4);
  d.fx = scene.uniform(0.0, 1.0);
  d.fy = scene.uniform(0.0, 1.0);
  d.look.white = scene.integer(170, 235);
  d.look.black = scene.integer(10, 40);
  d.look.card_size_mm = s.virtual_scene.card_size_mm;
  SceneRandom pose(mixSeed(base, 1));
  d.pose = randomStillPose(s, pose);
  SceneRandom conditions(mixSeed(base, 2));
  d.conditions = randomStillConditions(conditions);
  if (rig.any()) {
    SceneRandom effects(mixSeed(base, 3));
    d.rig = drawRigEffects(rig, s.target, d.look.card_size_mm, effects);
    if (d.rig.dim) {
      d.look.white = d.rig.dim_white;
      d.look.black = d.rig.dim_black;
    }
  }
  return d;
}

}  // namespace

Pose poseAlongRay(const CameraModel& camera, const Eigen::Vector2d& centre, double distance_mm, double tilt_deg,
                  double tilt_azimuth_deg, double inplane_deg) {
  const Eigen::Vector3d sight = backProjectIdeal(camera, centre).normalized();
  // A right-handed frame (e1, e2, sight) with e1 as close to the camera's X as it gets.
  const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - sight.x() * sight).normalized();
  const Eigen::Vector3d e2 = sight.cross(e1);
  Eigen::Matrix3d facing;
  facing << e1, e2, sight;  // target +Z along the line of sight: facing the camera head-on
  const Eigen::Vector3d axis = std::cos(tilt_azimuth_deg * kDeg) * e1 + std::sin(tilt_azimuth_deg * kDeg) * e2;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt_deg * kDeg, axis).toRotationMatrix() * facing *
                            Eigen::AngleAxisd(inplane_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return poseFromRt(R, distance_mm * sight);
}

bool cardInFrame(const CameraModel& camera, const TargetGeometry& target, double card_size_mm, const Pose& pose,
                 double margin_px) {
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  if (!(R.col(2).dot(T) > 1e-9 * T.norm())) return false;  // edge-on or seen from behind
  const double half = std::max(0.5 * card_size_mm, target.radius_mm);
  // The card's border, 32 points a side: its image bounds the card's, lens and all.
  const int n = 32;
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < n; ++k) {
      const double t = -half + 2.0 * half * k / n;
      const Eigen::Vector3d corner = side == 0 ? Eigen::Vector3d(t, -half, 0)
                                     : side == 1 ? Eigen::Vector3d(half, t, 0)
                                     : side == 2 ? Eigen::Vector3d(-t, half, 0)
                                                 : Eigen::Vector3d(-half, -t, 0);
      const Eigen::Vector3d P = R * corner + T;
      if (!(P.z() > 0.0)) return false;
      const Eigen::Vector2d p = distortPixel(camera, projectIdeal(camera, P));
      if (!(p.x() >= margin_px && p.y() >= margin_px && p.x() <= camera.width - 1.0 - margin_px &&
            p.y() <= camera.height - 1.0 - margin_px))
        return false;
    }
  }
  return true;
}

void composeOver(const cv::Mat& background, const std::function<void(int level, cv::Mat& out)>& paint,
                 cv::Mat& scene) {
  CV_Assert(background.type() == CV_8UC1);
  cv::Mat over_black, over_white;
  paint(0, over_black);
  paint(255, over_white);
  CV_Assert(over_black.type() == CV_8UC1 && over_black.size() == background.size() &&
            over_white.type() == CV_8UC1 && over_white.size() == background.size());
  cv::Mat a, b, photo;
  over_black.convertTo(a, CV_32F);
  over_white.convertTo(b, CV_32F);
  background.convertTo(photo, CV_32F);
  // scene = target + (1 - coverage) * photo, with (1 - coverage) = (b - a) / 255.
  cv::Mat show_through = (b - a) * (1.0 / 255.0);
  scene = a + show_through.mul(photo);
}

void composeTarget(const cv::Mat& background, const CameraModel& camera, const TargetGeometry& target,
                   const TargetLook& look, const Pose& pose, cv::Mat& scene) {
  CV_Assert(background.type() == CV_8UC1 && background.cols == camera.width && background.rows == camera.height);
  VirtualSceneOptions flat;  // the renderer's grey mode with no effects of its own
  flat.mode = RenderMode::Grey;
  flat.backdrop = Backdrop::Plain;  // the photograph is the backdrop
  flat.white_level = look.white;
  flat.black_level = look.black;
  flat.card_size_mm = look.card_size_mm;
  composeOver(
      background,
      [&](int level, cv::Mat& out) {
        flat.background_level = level;
        renderTarget(camera, target, flat, pose, out);
      },
      scene);
}

RealScenes::RealScenes(const Settings& settings, std::vector<std::string> photos, RigEffects rig)
    : settings_(settings), photos_(std::move(photos)), rig_(rig) {}

Pose RealScenes::stillPose(std::uint64_t seed, std::int64_t index) const {
  return drawStill(settings_, rig_, photos_.size(), seed, index).pose;
}

bool RealScenes::background(const std::string& path, double zoom, double fx, double fy, cv::Mat& out,
                            std::string& error) const {
  cv::Mat photo;
  if (!cache_.load(path, photo, error)) return false;
  out = fitBackground(photo, cv::Size(settings_.camera().width, settings_.camera().height), zoom, fx, fy);
  return true;
}

void RealScenes::paint(const ScenePainter& painter, const cv::Mat& background, const Pose& pose,
                       const TargetLook& look, cv::Mat& scene) const {
  if (painter)
    painter(background, pose, look, scene);
  else
    composeTarget(background, settings_.camera(), settings_.target, look, pose, scene);
}

bool RealScenes::still(std::uint64_t seed, std::int64_t index, bool with_target, RealSceneFrame& out,
                       std::string& error, const ScenePainter& painter) const {
  if (photos_.empty()) {
    error = "no photographs to draw the scenes over";
    return false;
  }
  const StillDraw d = drawStill(settings_, rig_, photos_.size(), seed, index);
  cv::Mat photo;
  if (!background(photos_[d.photo], d.zoom, d.fx, d.fy, photo, error)) return false;
  cv::Mat scene;
  if (with_target) {
    paint(painter, photo, d.pose, d.look, scene);
    paintRigEffects(d.rig, settings_.camera(), d.pose, scene);
    out.truth = d.pose;
    out.rig = d.rig;
  } else {
    photo.convertTo(scene, CV_32F);
    out.truth.reset();
    out.rig = {};
  }
  applyConditions(scene, d.conditions, out.image);
  out.background = photos_[d.photo];
  out.conditions = d.conditions;
  out.look = d.look;
  return true;
}

}  // namespace imagepro
