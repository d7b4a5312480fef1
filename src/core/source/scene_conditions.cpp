#include "core/source/scene_conditions.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace imagepro {

std::uint64_t mixSeed(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (index + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

SceneConditions randomStillConditions(SceneRandom& random) {
  SceneConditions c;
  c.light_shape = random.uniform(0.0, 1.0) < 0.5 ? LightShape::Ramp : LightShape::Vignette;
  c.light_amplitude = random.uniform(0.0, 0.4);
  c.light_direction_deg = random.uniform(0.0, 360.0);
  c.light_centre_u = random.uniform(0.0, 1.0);
  c.light_centre_v = random.uniform(0.0, 1.0);
  c.blur_sigma_px = random.uniform(0.5, 1.6);
  const bool moving = random.uniform(0.0, 1.0) < 1.0 / 3.0;
  const double streak = random.uniform(2.0, 6.0);
  const double streak_direction = random.uniform(0.0, 180.0);
  if (moving) {
    c.motion_blur_px = streak;
    c.motion_direction_deg = streak_direction;
  }
  c.noise_sigma = random.uniform(1.0, 6.0);
  c.jpeg_quality = random.integer(40, 95);
  c.noise_seed = random.bits();
  return c;
}

void lightField(const SceneConditions& c, cv::Size size, cv::Mat& factor) {
  factor.create(size, CV_32FC1);
  const double w = std::max(size.width - 1, 1);
  const double h = std::max(size.height - 1, 1);
  if (c.light_shape == LightShape::Ramp) {
    // s = (p - centre) . d, scaled so the frame's corners reach exactly -1 and +1.
    const double a = c.light_direction_deg * M_PI / 180.0;
    const double du = std::cos(a), dv = std::sin(a);
    const double reach = 0.5 * (std::abs(du) * w + std::abs(dv) * h);
    const double scale = reach > 0 ? 1.0 / reach : 0.0;
    for (int v = 0; v < size.height; ++v) {
      auto* row = factor.ptr<float>(v);
      for (int u = 0; u < size.width; ++u) {
        const double s = ((u - 0.5 * w) * du + (v - 0.5 * h) * dv) * scale;
        row[u] = static_cast<float>(c.light_gain * (1.0 + c.light_amplitude * s));
      }
    }
    return;
  }
  // Vignette: +1 at the light's centre, -1 at the farthest corner, quadratic between.
  const double cu = c.light_centre_u * w, cv_ = c.light_centre_v * h;
  const double far2 = std::max(cu, w - cu) * std::max(cu, w - cu) + std::max(cv_, h - cv_) * std::max(cv_, h - cv_);
  const double scale = far2 > 0 ? 2.0 / far2 : 0.0;
  for (int v = 0; v < size.height; ++v) {
    auto* row = factor.ptr<float>(v);
    for (int u = 0; u < size.width; ++u) {
      const double r2 = (u - cu) * (u - cu) + (v - cv_) * (v - cv_);
      row[u] = static_cast<float>(c.light_gain * (1.0 + c.light_amplitude * (1.0 - r2 * scale)));
    }
  }
}

cv::Mat motionKernel(double length_px, double direction_deg) {
  const int half = static_cast<int>(std::ceil(0.5 * length_px)) + 1;
  cv::Mat k = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32FC1);
  const double a = direction_deg * M_PI / 180.0;
  const double du = std::cos(a), dv = std::sin(a);
  // Samples every 1/16 px along the streak, each split bilinearly over its four pixels.
  const int samples = std::max(1, static_cast<int>(std::ceil(length_px * 16.0)));
  for (int i = 0; i <= samples; ++i) {
    const double t = length_px * (static_cast<double>(i) / samples - 0.5);
    const double x = half + t * du, y = half + t * dv;
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
    k.at<float>(y0, x0) += (1 - fx) * (1 - fy);
    k.at<float>(y0, x0 + 1) += fx * (1 - fy);
    k.at<float>(y0 + 1, x0) += (1 - fx) * fy;
    k.at<float>(y0 + 1, x0 + 1) += fx * fy;
  }
  k /= cv::sum(k)[0];
  return k;
}

void applyConditions(cv::Mat& scene, const SceneConditions& c, cv::Mat& out) {
  CV_Assert(scene.type() == CV_32FC1);
  if (c.light_amplitude != 0.0 || c.light_gain != 1.0) {
    cv::Mat factor;
    lightField(c, scene.size(), factor);
    scene = scene.mul(factor);
  }
  if (c.blur_sigma_px > 0.0)
    cv::GaussianBlur(scene, scene, cv::Size(0, 0), c.blur_sigma_px, c.blur_sigma_px, cv::BORDER_REFLECT);
  if (c.motion_blur_px > 0.0)
    cv::filter2D(scene, scene, -1, motionKernel(c.motion_blur_px, c.motion_direction_deg), cv::Point(-1, -1), 0,
                 cv::BORDER_REFLECT);
  if (c.noise_sigma > 0.0) {
    cv::Mat noise(scene.size(), CV_32FC1);
    cv::RNG rng(c.noise_seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, c.noise_sigma);
    scene += noise;
  }
  scene.convertTo(out, CV_8U);  // rounds and saturates
  if (c.jpeg_quality > 0) {
    std::vector<std::uint8_t> jpeg;
    cv::imencode(".jpg", out, jpeg, {cv::IMWRITE_JPEG_QUALITY, std::clamp(c.jpeg_quality, 1, 100)});
    out = cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE);
  }
}

}  // namespace imagepro
