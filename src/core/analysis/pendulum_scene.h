#pragma once
// The virtual pendulum of the g study (thesis 5.3.2): the Virtual source's pendulum
// motion (virtual_motion.h: exact large-amplitude swing of a target hanging from a
// pivot) rendered at the scene's frame rate, with optional motion blur: the exposure,
// centred on the frame's time, is rendered at several instants and averaged before the
// scene's noise is added (a camera's shutter integrates the moving image, thesis fig.
// 5.11). Frame i is at t = i / frame_rate_hz and carries the pose at t as its truth.
#include <opencv2/core.hpp>

#include <cstdint>
#include <string>

#include "core/settings/settings.h"
#include "core/source/source.h"

namespace imagepro {

struct MotionBlur {
  double exposure_s = 0.0;  // 0: a sharp frame
  int subframes = 8;        // renders averaged over the exposure
};

struct PendulumRenderWorkspace {
  cv::Mat sub;          // CV_8UC1, one instant
  cv::Mat sum, noise;   // CV_32FC1
};

// Renders the pendulum of settings.virtual_scene.pendulum (whatever the scene's motion
// kind) at time t_s into `out`.
void renderPendulumFrame(const Settings& settings, double t_s, const MotionBlur& blur, std::uint64_t frame_seed,
                         cv::Mat& out, PendulumRenderWorkspace& ws);

// The same as an endless frame source.
class PendulumSource final : public FrameSource {
 public:
  PendulumSource(const Settings& settings, const MotionBlur& blur);
  Status next(Frame& out) override;
  std::string lastError() const override { return {}; }
  double frameRateHz() const override;
  std::string describe() const override;

 private:
  Settings settings_;
  MotionBlur blur_;
  std::int64_t index_ = 0;
  PendulumRenderWorkspace ws_;
};

}  // namespace imagepro
