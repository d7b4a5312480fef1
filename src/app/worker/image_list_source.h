#pragma once
// The window's File source for still images (thesis 2.2): a list of image files shown
// one at a time, which the user steps through forward and back or plays to its end.
// Core's file source only goes forward; this one also seeks. One frame per call: the
// image at the position, read as 8-bit grey (image_file.h), then the position moves on.
#include <string>
#include <vector>

#include "core/source/source.h"

namespace imagepro::app {

class ImageListSource final : public FrameSource {
 public:
  explicit ImageListSource(std::vector<std::string> paths);

  // The image at the position (its index in the list, its file name without the folder,
  // timestamp 0); a file that cannot be read gives its Status and no image. After the
  // last image: EndOfStream.
  Status next(Frame& out) override;
  std::string lastError() const override { return error_; }
  double frameRateHz() const override { return 0.0; }  // not paced: played as fast as processed
  // "file img3.png" for one image, "file img3.png (3 of 8)" for a list.
  std::string describe() const override;

  int count() const { return static_cast<int>(paths_.size()); }
  // The image read last (-1 before the first).
  int shown() const { return shown_; }
  // The next call to next() reads image `index`, clamped to the list.
  void seek(int index);
  bool atEnd() const { return next_ >= count(); }
  const std::string& path(int index) const { return paths_.at(static_cast<std::size_t>(index)); }

 private:
  std::vector<std::string> paths_;
  int next_ = 0;
  int shown_ = -1;
  std::string error_;
};

}  // namespace imagepro::app
