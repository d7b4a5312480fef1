#include "core/analysis/pendulum_scene.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdio>

#include "core/source/virtual_motion.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {

namespace {
VirtualSceneOptions pendulumScene(const Settings& settings) {
  VirtualSceneOptions scene = settings.virtual_scene;
  scene.motion.kind = MotionKind::Pendulum;
  scene.backdrop = Backdrop::Plain;  // the thesis's study (5.3.2): its flat background
  return scene;
}
}  // namespace

namespace {

// One field, or the whole frame: the exposure about t_s.
void renderExposure(const Settings& settings, double t_s, const MotionBlur& blur, std::uint64_t frame_seed,
                    cv::Mat& out, PendulumRenderWorkspace& ws) {
  VirtualSceneOptions scene = pendulumScene(settings);
  if (!(blur.exposure_s > 0.0) || blur.subframes <= 1) {
    renderTarget(settings.camera(), settings.target, scene, virtualPoseAt(scene, t_s), out, frame_seed);
    return;
  }
  // Noise belongs to the sensor, after the exposure: render the instants without it.
  const double noise = scene.noise_sigma;
  scene.noise_sigma = 0.0;
  for (int j = 0; j < blur.subframes; ++j) {
    const double t = t_s + blur.exposure_s * ((j + 0.5) / blur.subframes - 0.5);
    renderTarget(settings.camera(), settings.target, scene, virtualPoseAt(scene, t), ws.sub, frame_seed);
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

}  // namespace

void renderPendulumFrame(const Settings& settings, double t_s, const MotionBlur& blur, bool interlaced,
                         std::uint64_t frame_seed, cv::Mat& out, PendulumRenderWorkspace& ws) {
  const double rate = settings.virtual_scene.frame_rate_hz;
  if (!interlaced || !(rate > 0.0)) {
    renderExposure(settings, t_s, blur, frame_seed, out, ws);
    return;
  }
  const double half_field = 0.25 / rate;
  renderExposure(settings, t_s - half_field, blur, frame_seed, out, ws);
  renderExposure(settings, t_s + half_field, blur, frame_seed, ws.field, ws);
  for (int y = 1; y < out.rows; y += 2) ws.field.row(y).copyTo(out.row(y));
}

PendulumSource::PendulumSource(const Settings& settings, const MotionBlur& blur, bool interlaced)
    : settings_(settings), blur_(blur), interlaced_(interlaced) {}

double PendulumSource::frameRateHz() const { return settings_.virtual_scene.frame_rate_hz; }

std::string PendulumSource::describe() const {
  char buf[96];
  std::snprintf(buf, sizeof buf, "virtual pendulum %.0f Hz%s%s", frameRateHz(),
                blur_.exposure_s > 0.0 ? ", motion blur" : "", interlaced_ ? ", interlaced" : "");
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
  renderPendulumFrame(settings_, out.timestamp_s, blur_, interlaced_, static_cast<std::uint64_t>(index_), out.image,
                      ws_);
  ++index_;
  return Status::Ok;
}

PendulumStillSource::PendulumStillSource(const Settings& settings, const PendulumStillParams& params)
    : settings_(settings), params_(params) {}

double PendulumStillSource::frameRateHz() const { return settings_.virtual_scene.frame_rate_hz; }

std::string PendulumStillSource::describe() const {
  char buf[96];
  std::snprintf(buf, sizeof buf, "virtual pendulum held still at %d angles over +-%.0f deg", params_.positions,
                params_.span_deg);
  return buf;
}

double PendulumStillSource::angleDeg(std::int64_t index) const {
  const std::int64_t position = index / std::max(1, params_.frames_per_position);
  if (params_.positions <= 1) return 0.0;
  return params_.span_deg * (2.0 * static_cast<double>(position) / (params_.positions - 1) - 1.0);
}

Status PendulumStillSource::next(Frame& out) {
  const double rate = settings_.virtual_scene.frame_rate_hz;
  if (!(rate > 0.0)) return Status::InvalidSettings;
  if (index_ >= static_cast<std::int64_t>(std::max(0, params_.positions)) * std::max(1, params_.frames_per_position))
    return Status::EndOfStream;
  out.index = index_;
  out.timestamp_s = static_cast<double>(index_) / rate;
  out.name.clear();
  const VirtualSceneOptions scene = pendulumScene(settings_);
  out.truth = pendulumPoseAtAngle(scene, angleDeg(index_));
  renderTarget(settings_.camera(), settings_.target, scene, *out.truth, out.image, static_cast<std::uint64_t>(index_));
  ++index_;
  return Status::Ok;
}

}  // namespace imagepro
