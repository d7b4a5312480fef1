#pragma once
// Poses in frames the user chooses (settings "frames", docs/conventions.md *Frames of
// reference*). A target's pose maps its own frame to the camera's; the pose of target b
// in target a's frame is a^-1 b, and in the world frame "Set origin" stored it is
// origin^-1 b. Neither depends on where the camera stands, so a reference target on a
// fixture measures a part against it while the camera is moved.
#include "core/common/geometry.h"
#include "core/pipeline/frame_result.h"
#include "core/settings/options.h"

namespace imagepro {

// `pose` (camera frame) in the frame whose camera-frame pose is `frame`.
Pose poseInFrameOf(const Pose& frame, const Pose& pose);

// The distance of the two disks' centres and the angle of their normals (target +Z).
TargetPairMeasure measurePair(const Pose& a, const Pose& b);

// Fills every found target's pose_in_reference and pose_in_world, the frame's own two
// (of its shown target, out.target_id) and measured_pair, from the targets' poses (with a
// set, out.targets; without one the frame's pose, id kLoneTargetId). The reference
// target has no pose in its own frame (it would be the identity).
void applyPoseFrames(const PoseFramesOptions& frames, FrameResult& out);

}  // namespace imagepro
