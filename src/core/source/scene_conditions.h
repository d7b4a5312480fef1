#pragma once
// The imaging conditions of a real-scene frame: what a webcam does to a
// scene between the light falling on it and the JPEG it delivers. Applied to the
// whole frame, target included, in this order: uneven light (a linear ramp in a
// random direction or a vignette around a random point, brightness scaled by
// 1 + amplitude * s with s in [-1, 1] over the frame, times a global gain), optical
// blur (Gaussian), motion blur (a straight streak, centred, so a blurred shape keeps
// its centroid), Gaussian noise, rounding to 8 bits, and a JPEG round trip.
#include <opencv2/core.hpp>

#include <cstdint>
#include <random>

namespace imagepro {

// Uniform numbers from a 64-bit Mersenne twister's raw bits: the same sequence on every
// standard library (std::uniform_real_distribution is not portable).
class SceneRandom {
 public:
  explicit SceneRandom(std::uint64_t seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(rng_() >> 11) * 0x1.0p-53); }
  // Whole number in [lo, hi].
  int integer(int lo, int hi) { return lo + static_cast<int>(rng_() % static_cast<std::uint64_t>(hi - lo + 1)); }
  std::uint64_t bits() { return rng_(); }

 private:
  std::mt19937_64 rng_;
};

// Mixes a seed and a stream index into an independent seed (splitmix64's finaliser).
std::uint64_t mixSeed(std::uint64_t seed, std::uint64_t index);

enum class LightShape : std::uint8_t { Ramp, Vignette };

struct SceneConditions {
  LightShape light_shape = LightShape::Ramp;
  double light_amplitude = 0.0;      // fraction: brightness spans 1 -+ amplitude over the frame
  double light_direction_deg = 0.0;  // ramp: brightest towards this image direction (u right, v down)
  double light_centre_u = 0.5;       // vignette: brightest point, fractions of width and height
  double light_centre_v = 0.5;
  double light_gain = 1.0;           // global brightness factor
  double blur_sigma_px = 0.0;        // optical blur, Gaussian sigma
  double motion_blur_px = 0.0;       // length of the motion streak; 0: none
  double motion_direction_deg = 0.0;
  double noise_sigma = 0.0;          // grey levels
  int jpeg_quality = 0;              // 1..100; 0: no JPEG round trip
  std::uint64_t noise_seed = 0;
};

// The real-scene stills' ranges: light +-0..40 %, blur 0.5-1.6 px, motion blur
// 2-6 px on a third of the frames, noise sigma 1-6, JPEG quality 40-95.
SceneConditions randomStillConditions(SceneRandom& random);

// The brightness factor of `c` at every pixel of a frame of `size` (CV_32FC1).
void lightField(const SceneConditions& c, cv::Size size, cv::Mat& factor);

// The kernel of a motion streak `length_px` long in `direction_deg`, centred, summing
// to 1 (CV_32FC1, odd size); the line is sampled finely, so any length and angle work.
cv::Mat motionKernel(double length_px, double direction_deg);

// Applies `c` to `scene` (CV_32FC1 grey levels, modified) and writes the 8-bit frame.
void applyConditions(cv::Mat& scene, const SceneConditions& c, cv::Mat& out);

}  // namespace imagepro
