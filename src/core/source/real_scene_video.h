#pragma once
// A real-scene video: one photograph, the target moving smoothly through it
// at 0.4-1.4 m (tilt 5-45 deg, turning, drifting across the frame, its card always
// wholly inside), the light drifting +-30 % (a global gain and a turning ramp), optical
// blur 0.8 px, noise sigma 2, JPEG quality 75, and the target hidden for `hidden`
// frames in the middle. Frame i is at t = i / 25 s; all motion phases and the
// photograph come from the seed.
#include <cstdint>
#include <string>
#include <vector>

#include "core/source/real_scene.h"

namespace imagepro {

class RealSceneVideo {
 public:
  // `scenes` (its settings and photographs) must outlive the video.
  RealSceneVideo(const RealScenes& scenes, std::uint64_t seed, int frames, int hidden = 12);

  int frames() const { return frames_; }
  // Frames [hiddenBegin(), hiddenEnd()) show no target.
  int hiddenBegin() const { return (frames_ - hidden_) / 2; }
  int hiddenEnd() const { return hiddenBegin() + hidden_; }
  bool hidden(int index) const { return index >= hiddenBegin() && index < hiddenEnd(); }
  // The target's pose at frame `index` (also while hidden: where it would be).
  Pose poseAt(int index) const;
  SceneConditions conditionsAt(int index) const;
  // Frame `index`; false with `error` when the photograph cannot be read. `painter` draws
  // something else than the target at the frame's pose (RealScenes::still's).
  bool frame(int index, RealSceneFrame& out, std::string& error, const ScenePainter& painter = {}) const;

  static constexpr double kFrameRateHz = 25.0;

 private:
  const RealScenes& scenes_;
  int frames_;
  int hidden_;
  std::size_t photo_ = 0;
  double zoom_ = 1, fx_ = 0.5, fy_ = 0.5;
  TargetLook look_;
  std::uint64_t noise_seed_ = 0;
  double phase_[9] = {};
};

}  // namespace imagepro
