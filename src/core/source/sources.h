#pragma once
// The frame sources of thesis 2.2 behind the FrameSource interface (source.h):
//  * File: a list of image files (image_file.h), one frame each, in the given order;
//  * Virtual perspective projection: the target (or the calibration pattern) rendered
//    by virtual_renderer.h at the pose of the scene's motion (virtual_motion.h) plus
//    the offset built up by the keys of appendix A, with its exact pose in Frame::truth.
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/settings/settings.h"
#include "core/source/image_file.h"
#include "core/source/source.h"
#include "core/source/virtual_motion.h"

namespace imagepro {

// One frame per file. A file that cannot be read gives its Status (the frame carries
// its index and name, no image) and the next call goes on with the next file; after
// the last file next() returns EndOfStream. Frame::name is the file name without the
// folder; files are not paced, so frameRateHz() is 0 and timestamps are 0.
std::unique_ptr<FrameSource> makeFileSource(std::vector<std::string> paths);

// What the Virtual source draws.
enum class VirtualContent : std::uint8_t { Target, Pattern };

// The Virtual source. Frame i is rendered at t = i / frame_rate_hz with frame seed i
// (so a run is reproducible), carries index i, timestamp t and the pose as truth.
// Every public function is thread-safe: the GUI may press keys or replace the
// settings while the worker thread calls next(); changes apply from the next frame.
class VirtualSource final : public FrameSource {
 public:
  explicit VirtualSource(const Settings& settings, VirtualContent content = VirtualContent::Target);

  Status next(Frame& out) override;
  std::string lastError() const override { return {}; }
  double frameRateHz() const override;
  std::string describe() const override;

  // Adds one key press to the pose offset (key_step_mm / key_step_deg of the scene).
  void pressKey(VirtualKey key);
  // Camera, target, pattern and virtual scene; the time and the key offset are kept.
  void setSettings(const Settings& settings);
  void setContent(VirtualContent content);
  void resetKeyOffset();
  // Back to frame 0 (t = 0).
  void restart();

  Pose keyOffset() const;
  std::int64_t nextIndex() const;
  // The pose frame `index` would be rendered at with the current settings and offset.
  Pose poseAt(std::int64_t index) const;

 private:
  mutable std::mutex mutex_;
  Settings settings_;
  VirtualContent content_;
  Pose offset_ = kZeroPoseOffset;
  std::int64_t index_ = 0;
};

std::unique_ptr<VirtualSource> makeVirtualSource(const Settings& settings,
                                                 VirtualContent content = VirtualContent::Target);

}  // namespace imagepro
