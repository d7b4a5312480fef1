#include "core/analysis/pendulum_scene.h"

#include <opencv2/imgproc.hpp>

#include <cstdio>

#include "core/source/virtual_motion.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {

namespace {
VirtualSceneOptions pendulumScene(const Settings& settings) {
  VirtualSceneOptions scene = settings.virtual_scene;
  scene.motion.kind = MotionKind::Pendulum;
  return scene;
}
}  // namespace

void renderPendulumFrame(const Settings& settings, double t_s, const MotionBlur& blur, std::uint64_t frame_seed,
                         cv::Mat& out, PendulumRenderWorkspace& ws) {
  VirtualSceneOptions scene = pendulumScene(settings);
  if (!(blur.exposure_s > 0.0) || blur.subframes <= 1) {
    renderTarget(settings.camera, settings.target, scene, virtualPoseAt(scene, t_s), out, frame_seed);
    return;
  }
  // Noise belongs to the sensor, after the exposure: render the instants without it.
  const double noise = scene.noise_sigma;
  scene.noise_sigma = 0.0;
  for (int j = 0; j < blur.subframes; ++j) {
    const double t = t_s + blur.exposure_s * ((j + 0.5) / blur.subframes - 0.5);
    renderTarget(settings.camera, settings.target, scene, virtualPoseAt(scene, t), ws.sub, frame_seed);
    if (j == 0)
      ws.sub.convertTo(ws.sum, CV_32F);
    else
      cv::add(ws.sum, ws.sub, ws.sum, cv::noArray(), CV_32F);
  }
  ws.sum *= 1.0 / blur.subframes;
  if (noise > 0.0 && scene.mode == RenderMode::Grey) {
    cv::RNG rng((0x2545f4914f6cdd1dULL * (frame_seed + 1)) ^ scene.seed);
    ws.noise.create(ws.sum.size(), CV_32FC1);
    rng.fill(ws.noise, cv::RNG::NORMAL, 0.0, noise);
    ws.sum += ws.noise;
  }
  if (scene.mode == RenderMode::Binary)
    cv::threshold(ws.sum, ws.sum, 127.5, 255.0, cv::THRESH_BINARY);  // a binary camera stays binary
  ws.sum.convertTo(out, CV_8U);
}

PendulumSource::PendulumSource(const Settings& settings, const MotionBlur& blur)
    : settings_(settings), blur_(blur) {}

double PendulumSource::frameRateHz() const { return settings_.virtual_scene.frame_rate_hz; }

std::string PendulumSource::describe() const {
  char buf[96];
  std::snprintf(buf, sizeof buf, "virtual pendulum %.0f Hz%s", frameRateHz(), blur_.exposure_s > 0.0 ? ", motion blur" : "");
  return buf;
}

Status PendulumSource::next(Frame& out) {
  const double rate = settings_.virtual_scene.frame_rate_hz;
  if (!(rate > 0.0)) return Status::InvalidSettings;
  out.index = index_;
  out.timestamp_s = static_cast<double>(index_) / rate;
  out.name.clear();
  const VirtualSceneOptions scene = pendulumScene(settings_);
  out.truth = virtualPoseAt(scene, out.timestamp_s);
  renderPendulumFrame(settings_, out.timestamp_s, blur_, static_cast<std::uint64_t>(index_), out.image, ws_);
  ++index_;
  return Status::Ok;
}

}  // namespace imagepro
