#include "core/source/bench_scene.h"

#include <opencv2/imgproc.hpp>

#include "core/source/virtual_motion.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {

Settings benchSceneSettings(cv::Size size) {
  Settings s;
  const double scale = size.width / 640.0;
  s.camera().width = size.width;
  s.camera().height = size.height;
  s.camera().pixel_size_mm = {0.01 / scale, 0.01 / scale};
  s.camera().principal_point_px = {(size.width - 1) / 2.0, (size.height - 1) / 2.0};
  VirtualSceneOptions& v = s.virtual_scene;
  v.mode = RenderMode::Grey;
  v.backdrop = Backdrop::Plain;  // the figures stay comparable with the thesis's frames
  v.clutter = 8;
  v.initial_pose = Pose{20.0, -25.0, 30.0, 0.0, 0.0, 900.0};
  v.motion.kind = MotionKind::Sinusoid;
  v.motion.axis = PoseAxis::Tx;
  v.motion.amplitude = 200.0;
  v.motion.period_s = 4.0;
  v.frame_rate_hz = 25.0;
  return s;
}

void degradeBenchFrame(cv::Mat& image, double blur_sigma_px, double noise_sigma, unsigned seed) {
  if (blur_sigma_px > 0) cv::GaussianBlur(image, image, {0, 0}, blur_sigma_px);
  if (noise_sigma > 0) {
    cv::Mat noise(image.size(), CV_16SC1);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::NORMAL, 0, noise_sigma);
    cv::Mat sum;
    image.convertTo(sum, CV_16SC1);
    sum += noise;
    sum.convertTo(image, CV_8UC1);
  }
}

Frame renderCleanBenchFrame(const Settings& scene, int index) {
  // Blur and noise are applied afterwards, identically to every kind of frame.
  VirtualSceneOptions clean = scene.virtual_scene;
  clean.noise_sigma = 0;
  clean.blur_sigma_px = 0;
  Frame f;
  f.index = index;
  f.timestamp_s = index / scene.virtual_scene.frame_rate_hz;
  f.truth = virtualPoseAt(scene.virtual_scene, f.timestamp_s);
  renderTarget(scene.camera(), scene.target, clean, *f.truth, f.image, static_cast<std::uint64_t>(index));
  return f;
}

std::vector<Frame> renderBenchSequence(const Settings& scene, int count) {
  std::vector<Frame> frames;
  frames.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    Frame f = renderCleanBenchFrame(scene, i);
    degradeBenchFrame(f.image, kBenchBlurSigmaPx, kBenchNoiseSigma, static_cast<unsigned>(i));
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace imagepro
