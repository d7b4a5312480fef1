#pragma once
// Ends a frame source after a number of frames: the virtual sources are endless, and
// a study runs them for as many frames as it asks.
#include <string>

#include "core/source/source.h"

namespace imagepro {

class FrameLimit final : public FrameSource {
 public:
  FrameLimit(FrameSource& inner, int frames) : inner_(inner), left_(frames) {}
  Status next(Frame& out) override { return left_-- > 0 ? inner_.next(out) : Status::EndOfStream; }
  std::string lastError() const override { return inner_.lastError(); }
  double frameRateHz() const override { return inner_.frameRateHz(); }
  std::string describe() const override { return inner_.describe(); }

 private:
  FrameSource& inner_;
  int left_;
};

}  // namespace imagepro
