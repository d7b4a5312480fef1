#pragma once
// A peer for the throughput comparison of `imagepro-studies bench-peers`: the target's pose
// by a pipeline composed of stock OpenCV calls — Otsu threshold, findContours,
// fitEllipseDirect, the ellipse with two holes as the target, then solvePnP on
// points sampled around the ellipse (matched to the disk's rim through the affine
// map of the ellipse, the offset spot fixing the angle) plus the two spots.
#include <opencv2/core.hpp>

#include <vector>

#include "core/common/geometry.h"
#include "core/common/status.h"

namespace imagepro::studies {

struct OpenCvPeerWorkspace {
  cv::Mat binary;
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  std::vector<cv::Point3f> object_points;
  std::vector<cv::Point2f> image_points;
};

Status opencvPeerPose(const cv::Mat& grey, const CameraModel& camera, const TargetGeometry& target,
                      OpenCvPeerWorkspace& ws, Pose& out);

}  // namespace imagepro::studies
