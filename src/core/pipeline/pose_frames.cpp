#include "core/pipeline/pose_frames.h"

#include <algorithm>
#include <cmath>

#include "core/settings/target_set.h"

namespace imagepro {

namespace {

// The pose of target `id` in this frame, or none.
const Pose* poseOfTarget(const FrameResult& out, int id) {
  if (id < 0) return nullptr;
  if (!out.set_of_targets) return id == out.target_id && ok(out.status) && out.pose ? &*out.pose : nullptr;
  for (const TargetSummary& t : out.targets)
    if (t.target_id == id && ok(t.status) && t.pose) return &*t.pose;
  return nullptr;
}

void inFrames(const PoseFramesOptions& frames, const Pose* reference, int id, const Pose& pose,
              std::optional<Pose>& in_reference, std::optional<Pose>& in_world) {
  in_reference.reset();
  in_world.reset();
  if (reference && id != frames.reference_target) in_reference = poseInFrameOf(*reference, pose);
  if (frames.origin_set) in_world = poseInFrameOf(frames.origin, pose);
}

}  // namespace

Pose poseInFrameOf(const Pose& frame, const Pose& pose) {
  const Eigen::Matrix3d Rf = rotationMatrix(frame);
  const Eigen::Matrix3d R = Rf.transpose() * rotationMatrix(pose);
  const Eigen::Vector3d T = Rf.transpose() * (translation(pose) - translation(frame));
  return poseFromRt(R, T);
}

TargetPairMeasure measurePair(const Pose& a, const Pose& b) {
  TargetPairMeasure m;
  m.distance_mm = (translation(a) - translation(b)).norm();
  const double c = rotationMatrix(a).col(2).dot(rotationMatrix(b).col(2));
  m.angle_deg = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
  return m;
}

void applyPoseFrames(const PoseFramesOptions& frames, FrameResult& out) {
  const Pose* reference = poseOfTarget(out, frames.reference_target);
  for (TargetSummary& t : out.targets) {
    t.pose_in_reference.reset();
    t.pose_in_world.reset();
    if (out.set_of_targets && ok(t.status) && t.pose)
      inFrames(frames, reference, t.target_id, *t.pose, t.pose_in_reference, t.pose_in_world);
  }
  out.pose_in_reference.reset();
  out.pose_in_world.reset();
  if (ok(out.status) && out.pose)
    inFrames(frames, reference, out.target_id, *out.pose, out.pose_in_reference, out.pose_in_world);
  out.measured_pair.reset();
  const Pose* a = poseOfTarget(out, frames.measured_targets[0]);
  const Pose* b = poseOfTarget(out, frames.measured_targets[1]);
  if (a && b && frames.measured_targets[0] != frames.measured_targets[1]) out.measured_pair = measurePair(*a, *b);
}

}  // namespace imagepro
