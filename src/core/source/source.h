#pragma once
// Frame sources (thesis 2.2): File, image sequence, Camera (V4L2), video file and
// Virtual perspective projection. The one interface in the core: the engine pulls
// frames from whichever source is selected without knowing which it is.
#include <memory>
#include <string>

#include "core/common/frame.h"
#include "core/common/status.h"

namespace imagepro {

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // Fills `out` with the next frame. A non-Ok status names the problem; for a live
  // source the next call may succeed again (the frame loop goes on).
  virtual Status next(Frame& out) = 0;
  // Human-readable description of the last error (file name and reason), if any.
  virtual std::string lastError() const = 0;
  // Nominal frame rate for pacing, 0 when the source is not paced (files).
  virtual double frameRateHz() const = 0;
  // Short description for the status bar ("virtual 25 Hz", "file sample01.png").
  virtual std::string describe() const = 0;
};

}  // namespace imagepro
