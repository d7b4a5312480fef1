#include "core/pipeline/pose_frames.h"

#include <gtest/gtest.h>

#include "core/settings/target_set.h"
#include "support/expect_pose.h"

namespace imagepro {
namespace {

// b's pose in a's frame composed with a's gives b back; a pose in its own frame is the identity.
TEST(PoseFrames, APoseInAnothersFrameComposesBack) {
  const Pose a{20, -35, 60, 100, -50, 900};
  const Pose b{-10, 25, -120, -80, 40, 1300};
  const Pose inA = poseInFrameOf(a, b);
  const Eigen::Matrix3d R = rotationMatrix(a) * rotationMatrix(inA);
  const Eigen::Vector3d T = rotationMatrix(a) * translation(inA) + translation(a);
  test::expectPose(poseFromRt(R, T), b, 1e-9);
  test::expectPose(poseInFrameOf(a, a), Pose{0, 0, 0, 0, 0, 0}, 1e-9);
  // Moving the camera (both poses by one motion) leaves it unchanged.
  const Eigen::Matrix3d M = rotationMatrix(Pose{5, 10, 15, 0, 0, 0});
  const Eigen::Vector3d d(30, -20, 100);
  const Pose a2 = poseFromRt(M * rotationMatrix(a), M * translation(a) + d);
  const Pose b2 = poseFromRt(M * rotationMatrix(b), M * translation(b) + d);
  test::expectPose(poseInFrameOf(a2, b2), inA, 1e-9);
}

TEST(PoseFrames, ThePairsDistanceAndAngle) {
  const TargetPairMeasure m = measurePair(Pose{0, 0, 0, -100, 0, 1000}, Pose{0, 90, 0, 100, 0, 1000});
  EXPECT_NEAR(m.distance_mm, 200.0, 1e-9);
  EXPECT_NEAR(m.angle_deg, 90.0, 1e-9);
}

// The lone target: the world frame of "Set origin" and the settings' ids checked.
TEST(PoseFrames, TheWorldFrameOfTheLoneTargetAndIdsThatNameNoTarget) {
  PoseFramesOptions frames;
  frames.origin_set = true;
  frames.origin = Pose{10, 20, 30, 40, 50, 800};
  FrameResult r;
  r.status = Status::Ok;
  r.pose = frames.origin;
  r.target_id = kLoneTargetId;
  applyPoseFrames(frames, r);
  ASSERT_TRUE(r.pose_in_world.has_value());
  test::expectPose(*r.pose_in_world, Pose{0, 0, 0, 0, 0, 0}, 1e-9);
  EXPECT_FALSE(r.pose_in_reference.has_value());

  EXPECT_EQ(framesProblem(frames, {}), "");
  frames.reference_target = 3;
  EXPECT_NE(framesProblem(frames, {}).find("frames.reference_target: 3"), std::string::npos);
  const std::vector<TargetSpec> set{TargetSpec{3, "", {}}, TargetSpec{4, "", {}}};
  EXPECT_EQ(framesProblem(frames, set), "");
  frames.measured_targets = {4, 4};
  EXPECT_NE(framesProblem(frames, set).find("must differ"), std::string::npos);
}

}  // namespace
}  // namespace imagepro
