// The ellipse stage reuses its workspace: once warmed up on a frame, detecting again
// allocates nothing (real-time rule: no per-frame heap allocation in steady state).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <functional>
#include <new>

#include "core/ellipse/detect.h"
#include "core/source/virtual_renderer.h"
#include "scenes.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
// GCC at -O1 (the sanitizer builds) takes the free() below for a mismatch with the
// replaced operator new, which is malloc() underneath.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace imagepro {
namespace {

long allocationsOf(const std::function<void()>& work) {
  const long before = g_allocations.load();
  work();
  return g_allocations.load() - before;
}

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
