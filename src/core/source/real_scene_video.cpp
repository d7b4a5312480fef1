#include "core/source/real_scene_video.h"

#include <algorithm>
#include <cmath>

namespace imagepro {

namespace {
constexpr double kTwoPi = 2.0 * M_PI;
}

RealSceneVideo::RealSceneVideo(const RealScenes& scenes, std::uint64_t seed, int frames, int hidden)
    : scenes_(scenes), frames_(std::max(frames, 0)), hidden_(std::clamp(hidden, 0, std::max(frames, 0))) {
  SceneRandom random(mixSeed(seed, 0x766964656fULL));  // "video"
  const std::size_t n = scenes.photos().size();
  photo_ = n ? static_cast<std::size_t>(random.bits() % n) : 0;
  zoom_ = random.uniform(1.0, 1.4);
  fx_ = random.uniform(0.0, 1.0);
  fy_ = random.uniform(0.0, 1.0);
  look_.white = random.integer(170, 235);
  look_.black = random.integer(10, 40);
  look_.card_size_mm = scenes.settings().virtual_scene.card_size_mm;
  noise_seed_ = random.bits();
  for (double& p : phase_) p = random.uniform(0.0, kTwoPi);
}

Pose RealSceneVideo::poseAt(int index) const {
  const Settings& s = scenes_.settings();
  const CameraModel& cam = s.camera();
  const double t = index / kFrameRateHz;
  // Incommensurate periods (seconds), so the path does not repeat within a video.
  const double distance = 900.0 + 500.0 * std::sin(kTwoPi * t / 6.1 + phase_[0]);
  const double tilt = 25.0 + 20.0 * std::sin(kTwoPi * t / 3.7 + phase_[1]);
  const double azimuth = phase_[2] * 180.0 / M_PI + 40.0 * t;
  const double inplane = phase_[3] * 180.0 / M_PI + 30.0 * std::sin(kTwoPi * t / 7.3 + phase_[4]);
  const double ou = 0.5 * (cam.width - 1.0) * 0.8 * std::sin(kTwoPi * t / 4.3 + phase_[5]);
  const double ov = 0.5 * (cam.height - 1.0) * 0.8 * std::sin(kTwoPi * t / 5.3 + phase_[6]);
  const Eigen::Vector2d centre(cam.u0(), cam.v0());
  auto at = [&](double k) {
    return poseAlongRay(cam, centre + k * Eigen::Vector2d(ou, ov), distance, tilt, azimuth, inplane);
  };
  // Drawn in towards the principal point as far as needed to keep the card in the frame
  // (the largest fraction of the offset that fits, so the path stays continuous).
  if (cardInFrame(cam, s.target, look_.card_size_mm, at(1.0), 2.0)) return at(1.0);
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    (cardInFrame(cam, s.target, look_.card_size_mm, at(mid), 2.0) ? lo : hi) = mid;
  }
  return at(lo);
}

SceneConditions RealSceneVideo::conditionsAt(int index) const {
  const double t = index / kFrameRateHz;
  SceneConditions c;
  // Gain 1 +- 0.15 times a ramp of +-0.13: the light at any pixel stays within +-30 %.
  c.light_gain = 1.0 + 0.15 * std::sin(kTwoPi * t / 5.0 + phase_[7]);
  c.light_shape = LightShape::Ramp;
  c.light_amplitude = 0.13;
  c.light_direction_deg = phase_[8] * 180.0 / M_PI + 20.0 * t;
  c.blur_sigma_px = 0.8;
  c.noise_sigma = 2.0;
  c.jpeg_quality = 75;
  c.noise_seed = mixSeed(noise_seed_, static_cast<std::uint64_t>(index));
  return c;
}

bool RealSceneVideo::frame(int index, RealSceneFrame& out, std::string& error, const ScenePainter& painter) const {
  if (scenes_.photos().empty()) {
    error = "no photographs to draw the scenes over";
    return false;
  }
  cv::Mat photo;
  const std::string& path = scenes_.photos()[photo_];
  if (!scenes_.background(path, zoom_, fx_, fy_, photo, error)) return false;
  cv::Mat scene;
  if (hidden(index)) {
    photo.convertTo(scene, CV_32F);
    out.truth.reset();
  } else {
    const Pose pose = poseAt(index);
    scenes_.paint(painter, photo, pose, look_, scene);
    out.truth = pose;
  }
  out.conditions = conditionsAt(index);
  applyConditions(scene, out.conditions, out.image);
  out.background = path;
  out.look = look_;
  return true;
}

}  // namespace imagepro
