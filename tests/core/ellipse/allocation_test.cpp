// The ellipse stage reuses its workspace: once warmed up on a frame, detecting again
// allocates nothing (real-time rule: no per-frame heap allocation in steady state).
#include <gtest/gtest.h>

#include "core/ellipse/detect.h"
#include "core/source/virtual_renderer.h"
#include "scenes.h"
#include "support/allocation_counter.h"

namespace imagepro {
namespace {

using test::allocationsOf;

TEST(EllipseAllocation, CounterCounts) {
  EXPECT_EQ(allocationsOf([] { ::operator delete(::operator new(16)); }), 1);
}

TEST(EllipseAllocation, SteadyStateAllocatesNothing) {
  VirtualSceneOptions scene;
  scene.clutter = 20;
  scene.noise_sigma = 3.0;
  cv::Mat frame;
  renderTarget(CameraModel{}, TargetGeometry{}, scene, Pose{20, 10, 0, 30, 20, 800}, frame, 1);
  test::PathPipeline pipe;
  ASSERT_EQ(pipe.run(frame), Status::Ok);
  for (const EllipseMethod method : {EllipseMethod::DirectFit, EllipseMethod::Bennett}) {
    EllipseOptions o;
    o.method = method;
    EllipseWorkspace ws;
    std::vector<TargetDetection> out;
    ASSERT_EQ(detectTarget(o, TargetGeometry{}, pipe.paths, frame.size(), ws, out), Status::Ok);  // warm-up
    EXPECT_EQ(allocationsOf([&] { detectTarget(o, TargetGeometry{}, pipe.paths, frame.size(), ws, out); }), 0);
    detectEllipses(o, pipe.paths, frame.size(), ws, out);
    EXPECT_EQ(allocationsOf([&] { detectEllipses(o, pipe.paths, frame.size(), ws, out); }), 0);
  }
}

}  // namespace
}  // namespace imagepro
