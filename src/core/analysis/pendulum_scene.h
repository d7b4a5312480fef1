#pragma once
// The virtual pendulum of the g study (thesis 5.3.2): the Virtual source's pendulum
// motion (virtual_motion.h: exact large-amplitude swing of a target hanging from a
// pivot) rendered at the scene's frame rate, with optional motion blur: the exposure,
// centred on the frame's time, is rendered at several instants and averaged before the
// scene's noise is added (a camera's shutter integrates the moving image, thesis fig.
// 5.11), and optionally interlaced as the thesis's camera was (fig. 5.11): the even
// rows (the first field) are exposed half a field time before the frame's time and the
// odd rows half a field time after, a field being half the frame time (50 fields a
// second at 25 frames), each field with its own blur. Frame i is at t = i /
// frame_rate_hz and carries the pose at t as its truth.
//
// The still recording of the thesis's length measurement: the pendulum held still at
// a few angles along its arc, a few frames at each.
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
  cv::Mat field;        // CV_8UC1, the second field
};

// Renders the pendulum of settings.virtual_scene.pendulum (whatever the scene's motion
// kind) at time t_s into `out`; `interlaced` at the settings' frame rate.
void renderPendulumFrame(const Settings& settings, double t_s, const MotionBlur& blur, bool interlaced,
                         std::uint64_t frame_seed, cv::Mat& out, PendulumRenderWorkspace& ws);

// The same as an endless frame source.
class PendulumSource final : public FrameSource {
 public:
  PendulumSource(const Settings& settings, const MotionBlur& blur, bool interlaced = false);
  Status next(Frame& out) override;
  std::string lastError() const override { return {}; }
  double frameRateHz() const override;
  std::string describe() const override;

 private:
  Settings settings_;
  MotionBlur blur_;
  bool interlaced_ = false;
  std::int64_t index_ = 0;
  PendulumRenderWorkspace ws_;
};

// Where the pendulum is held for the still recording.
struct PendulumStillParams {
  int positions = 5;            // angles, evenly spread over +-span_deg (the thesis held five)
  double span_deg = 20.0;
  int frames_per_position = 5;  // frames at each
};

// The still recording as a frame source: positions x frames_per_position frames,
// frame i at i / frame_rate_hz, each with its pose as the truth, then EndOfStream.
class PendulumStillSource final : public FrameSource {
 public:
  PendulumStillSource(const Settings& settings, const PendulumStillParams& params);
  Status next(Frame& out) override;
  std::string lastError() const override { return {}; }
  double frameRateHz() const override;
  std::string describe() const override;
  // The angle (deg) of frame `index`.
  double angleDeg(std::int64_t index) const;

 private:
  Settings settings_;
  PendulumStillParams params_;
  std::int64_t index_ = 0;
};

}  // namespace imagepro
