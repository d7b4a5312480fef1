#pragma once
// The AprilTag 3 peer of `imagepro-studies bench-peers` (Debian's libapriltag, family
// tag36h11): draws the tag at a target's pose into a frame, and detects it and
// estimates its pose with the library's own calls.
#include <opencv2/core.hpp>

#include <memory>

#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro::studies {

class AprilTagPeer {
 public:
  // `tag_size_mm`: side of the tag's black square (the disk's diameter in the comparison).
  AprilTagPeer(const CameraModel& camera, double tag_size_mm);
  ~AprilTagPeer();
  AprilTagPeer(const AprilTagPeer&) = delete;
  AprilTagPeer& operator=(const AprilTagPeer&) = delete;

  // Paints tag 0 (with its white border) into `frame` as the camera sees it at `pose`
  // (pose convention of docs/conventions.md, the tag centred on the target's origin).
  void drawTag(const Pose& pose, cv::Mat& frame) const;
  // Detects the tag and estimates its pose; NoTarget when not found.
  Status detect(const cv::Mat& grey, Pose& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace imagepro::studies
