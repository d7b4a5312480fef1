#include "core/analysis/two_targets.h"

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "core/pipeline/pose_frames.h"
#include "core/source/virtual_renderer.h"

namespace imagepro {

namespace {
constexpr double kRadPerDeg = M_PI / 180.0;
}  // namespace

TwoTargetMeasurement measureBetween(const Pose& a, const Pose& b) {
  const TargetPairMeasure m = measurePair(a, b);
  return {m.distance_mm, m.angle_deg};
}

Status measureTwoTargets(const MultiTargetResult& frame, TwoTargetMeasurement& out) {
  if (!ok(frame.status)) return frame.status;
  const int n = frame.reconstructed();
  if (n > 2) return Status::AmbiguousTarget;
  if (n < 2) {
    for (const ReconstructedTarget& t : frame.targets)
      if (!ok(t.status)) return t.status;
    return Status::TooFewTargets;
  }
  const ReconstructedTarget* found[2] = {nullptr, nullptr};
  for (const ReconstructedTarget& t : frame.targets)
    if (ok(t.status)) found[found[0] ? 1 : 0] = &t;
  out = measureBetween(found[0]->pose, found[1]->pose);
  return Status::Ok;
}

std::array<Pose, 2> twoTargetPoses(const TwoTargetObject& object, const Pose& object_pose) {
  const Eigen::Matrix3d R = rotationMatrix(object_pose);
  const Eigen::Vector3d T = translation(object_pose);
  const double half_angle = 0.5 * object.angle_deg * kRadPerDeg;
  const double half_spacing = 0.5 * object.spacing_mm;
  const Eigen::Matrix3d left = Eigen::AngleAxisd(half_angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d right = Eigen::AngleAxisd(-half_angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return {poseFromRt(R * left, R * Eigen::Vector3d(-half_spacing, 0.0, 0.0) + T),
          poseFromRt(R * right, R * Eigen::Vector3d(half_spacing, 0.0, 0.0) + T)};
}

bool twoTargetObjectFits(const TwoTargetObject& object, double card_size_mm) {
  if (!(object.angle_deg > 0.0 && object.angle_deg < 180.0) || !(object.spacing_mm > 0.0)) return false;
  // Each centre lies spacing / (2 cos(angle / 2)) from the edge, along its face.
  const double to_edge = object.spacing_mm / (2.0 * std::cos(0.5 * object.angle_deg * kRadPerDeg));
  return to_edge >= 0.5 * card_size_mm;
}

Pose twoTargetStudyPosition(int position) {
  switch (position) {
    case 2: return Pose{6.0, 4.0, 3.0, -40.0, 25.0, 850.0};
    case 3: return Pose{-8.0, -6.0, -5.0, 45.0, -20.0, 700.0};
    default: return Pose{0.0, 0.0, 0.0, 0.0, 0.0, 750.0};
  }
}

void applyStudyLighting(StudyLighting lighting, VirtualSceneOptions& scene) {
  switch (lighting) {
    case StudyLighting::Natural:
      scene.white_level = 165;
      scene.black_level = 12;
      scene.background_level = 70;
      scene.illumination_gradient = 0.15;
      break;
    case StudyLighting::Extra:
      scene.white_level = 235;
      scene.black_level = 25;
      scene.background_level = 120;
      scene.illumination_gradient = 0.0;
      break;
  }
}

void renderTwoTargets(const CameraModel& camera, const TargetGeometry& target, const VirtualSceneOptions& scene,
                      const TwoTargetObject& object, const Pose& object_pose, cv::Mat& out,
                      std::uint64_t frame_seed, TwoTargetRenderWorkspace& ws) {
  const std::array<Pose, 2> poses = twoTargetPoses(object, object_pose);
  const bool binary = scene.mode == RenderMode::Binary;

  // Each target alone, without the effects that must act on the whole image once.
  VirtualSceneOptions clean = scene;
  clean.noise_sigma = 0.0;
  clean.blur_sigma_px = 0.0;
  clean.illumination_gradient = 0.0;
  clean.backdrop = Backdrop::Plain;  // the thesis's study: the cards on one flat grey
  renderTarget(camera, target, clean, poses[0], ws.left, frame_seed);
  clean.clutter = 0;
  renderTarget(camera, target, clean, poses[1], ws.right, frame_seed);
  // Coverage of the right card: its card and disk at 255 on a 0 background, anti-aliased
  // like the grey render (pixel centres only for a binary image).
  VirtualSceneOptions cover = clean;
  cover.mode = RenderMode::Grey;
  cover.white_level = cover.black_level = 255;
  cover.background_level = 0;
  if (binary) cover.supersampling = 1;
  renderTarget(camera, target, cover, poses[1], ws.cover, frame_seed);

  if (binary) {
    ws.left.copyTo(out);
    cv::compare(ws.cover, 127, ws.mask, cv::CMP_GT);
    ws.right.copyTo(out, ws.mask);
    return;
  }
  // An edge pixel of the right card already mixes the card with the background by its
  // coverage alpha: right = alpha card + (1 - alpha) background. Over the left render,
  // grey = alpha card + (1 - alpha) left = right + (1 - alpha) (left - background).
  ws.left.convertTo(ws.difference, CV_32F, 1.0, -std::clamp(clean.background_level, 0, 255));
  ws.cover.convertTo(ws.alpha, CV_32F, -1.0 / 255.0, 1.0);
  cv::multiply(ws.difference, ws.alpha, ws.difference);
  ws.right.convertTo(ws.grey, CV_32F);
  ws.grey += ws.difference;

  const int width = ws.grey.cols;
  const int height = ws.grey.rows;
  if (scene.illumination_gradient != 0.0) {
    const double g = scene.illumination_gradient;
    const double span = std::max(width - 1, 1);
    for (int v = 0; v < height; ++v) {
      auto* row = ws.grey.ptr<float>(v);
      for (int u = 0; u < width; ++u) row[u] *= static_cast<float>(1.0 + g * (u / span - 0.5));
    }
  }
  if (scene.blur_sigma_px > 0.0)
    cv::GaussianBlur(ws.grey, ws.grey, cv::Size(0, 0), scene.blur_sigma_px, scene.blur_sigma_px,
                     cv::BORDER_REPLICATE);
  if (scene.noise_sigma > 0.0) {
    cv::RNG rng((0x9e3779b97f4a7c15ULL * (frame_seed + 1)) ^ scene.seed);
    ws.noise.create(height, width, CV_32FC1);
    rng.fill(ws.noise, cv::RNG::NORMAL, 0.0, scene.noise_sigma);
    ws.grey += ws.noise;
  }
  ws.grey.convertTo(out, CV_8U);
}

}  // namespace imagepro
