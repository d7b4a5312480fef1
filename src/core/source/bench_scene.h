#pragma once
// The realistic scene every throughput measurement uses, so that `imagepro-cli bench`
// and the Google benchmarks time the same frames: grey 640x480-class frames of the
// target 900 mm away, tilted 20 deg / -25 deg and turned 30 deg, swinging +-200 mm
// sideways over 4 s in front of 8 clutter objects, blurred (0.8 px) and noisy (3 grey
// levels) after rendering. The field of view is the same at every resolution.
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/frame.h"
#include "core/settings/settings.h"

namespace imagepro {

inline constexpr double kBenchBlurSigmaPx = 0.8;
inline constexpr double kBenchNoiseSigma = 3.0;

// The scene's settings for frames of `size` (defaults otherwise).
Settings benchSceneSettings(cv::Size size);

// Gaussian blur, then Gaussian noise from `seed`, in place (CV_8UC1).
void degradeBenchFrame(cv::Mat& image, double blur_sigma_px, double noise_sigma, unsigned seed);

// Frame i of the scene rendered without blur and noise (truth = the pose at i / rate).
Frame renderCleanBenchFrame(const Settings& scene, int index);

// `count` degraded frames of the scene.
std::vector<Frame> renderBenchSequence(const Settings& scene, int count);

}  // namespace imagepro
