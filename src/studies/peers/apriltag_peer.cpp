#include "studies/peers/apriltag_peer.h"

#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/apriltag_pose.h>
#include <apriltag/tag36h11.h>
}

#include <Eigen/Core>
#include <cstdlib>

namespace imagepro::studies {

namespace {
constexpr int kUpscale = 16;  // tag cells drawn 16x16 before warping, for clean edges
}

struct AprilTagPeer::Impl {
  CameraModel camera;
  double tag_size_mm = 100.0;
  apriltag_family_t* family = nullptr;
  apriltag_detector_t* detector = nullptr;
  cv::Mat tag_image;  // the tag with its white border, upscaled
  int cells = 10;     // tag image width in cells (border included)
  int black_cells = 8;
};

AprilTagPeer::AprilTagPeer(const CameraModel& camera, double tag_size_mm) : impl_(std::make_unique<Impl>()) {
  impl_->camera = camera;
  impl_->tag_size_mm = tag_size_mm;
  impl_->family = tag36h11_create();
  impl_->detector = apriltag_detector_create();
  apriltag_detector_add_family(impl_->detector, impl_->family);
  impl_->detector->nthreads = 1;  // one core, like ImagePro's pipeline
  impl_->detector->quad_decimate = 2.0f;

  image_u8_t* tag = apriltag_to_image(impl_->family, 0);
  impl_->cells = tag->width;
  impl_->black_cells = impl_->family->width_at_border;
  cv::Mat small(tag->height, tag->width, CV_8UC1, tag->buf, static_cast<size_t>(tag->stride));
  cv::resize(small, impl_->tag_image, {}, kUpscale, kUpscale, cv::INTER_NEAREST);
  image_u8_destroy(tag);
}

AprilTagPeer::~AprilTagPeer() {
  apriltag_detector_destroy(impl_->detector);
  tag36h11_destroy(impl_->family);
}

void AprilTagPeer::drawTag(const Pose& pose, cv::Mat& frame) const {
  const Impl& m = *impl_;
  const double cell = m.tag_size_mm / m.black_cells;
  const double half = m.cells / 2.0;
  // Tag image pixel (i, j) -> target plane (x, y) -> camera -> pixels.
  const double s = cell / kUpscale;
  const Eigen::Matrix3d R = rotationMatrix(pose);
  const Eigen::Vector3d T = translation(pose);
  Eigen::Matrix3d K;
  K << m.camera.fu(), 0, m.camera.u0(), 0, m.camera.fv(), m.camera.v0(), 0, 0, 1;
  Eigen::Matrix3d plane;
  plane.col(0) = R.col(0);
  plane.col(1) = R.col(1);
  plane.col(2) = T;
  Eigen::Matrix3d S;
  S << s, 0, (0.5 * s) - half * cell, 0, s, (0.5 * s) - half * cell, 0, 0, 1;
  const Eigen::Matrix3d H = K * plane * S;
  cv::Matx33d Hcv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
  cv::warpPerspective(m.tag_image, frame, Hcv, frame.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
}

Status AprilTagPeer::detect(const cv::Mat& grey, Pose& out) {
  if (grey.empty() || grey.type() != CV_8UC1) return Status::EmptyFrame;
  image_u8_t im{grey.cols, grey.rows, static_cast<int32_t>(grey.step), grey.data};
  zarray_t* detections = apriltag_detector_detect(impl_->detector, &im);
  Status status = Status::NoTarget;
  for (int i = 0; i < zarray_size(detections); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(detections, i, &det);
    if (det->id != 0) continue;
    apriltag_detection_info_t info{det, impl_->tag_size_mm, impl_->camera.fu(), impl_->camera.fv(),
                                   impl_->camera.u0(), impl_->camera.v0()};
    apriltag_pose_t pose;
    estimate_tag_pose(&info, &pose);
    Eigen::Matrix3d R;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R(r, c) = MATD_EL(pose.R, r, c);
    const Eigen::Vector3d T(MATD_EL(pose.t, 0, 0), MATD_EL(pose.t, 1, 0), MATD_EL(pose.t, 2, 0));
    out = poseFromRt(R, T);
    // libapriltag does not export matd_destroy; its matrices are single calloc blocks.
    std::free(pose.R);
    std::free(pose.t);
    status = Status::Ok;
    break;
  }
  apriltag_detections_destroy(detections);
  return status;
}

}  // namespace imagepro::studies
