// Steady state of the whole frame loop: once the engine's buffers have grown to a
// frame's size, processing a frame allocates nothing at all — no operator new and no
// malloc underneath (cv::Mat buffers, OpenCV's own scratch) — full frame or tracked,
// whether the target is found or lost. Counts every allocation of this process; a
// sanitizer build owns malloc itself and counts nothing, so there the tests are skipped.
#include <gtest/gtest.h>

#include <cstdlib>

#include <opencv2/core/utility.hpp>

#include "cli/allocation_counter.h"
#include "core/pipeline/engine.h"
#include "core/source/bench_scene.h"
#include "core/source/target_set_scene.h"

namespace imagepro {
namespace {

constexpr int kFrames = 40;

const std::vector<Frame>& benchFrames() {
  static const std::vector<Frame> frames = renderBenchSequence(benchSceneSettings({640, 480}), kFrames);
  return frames;
}

constexpr const char* kNoCounting =
    "this build counts no allocations (a sanitizer owns malloc, or IMAGEPRO_COUNT_ALLOCATIONS=OFF)";

// The counter sees what the frame loop could allocate: malloc underneath, operator
// new and a cv::Mat's buffer. Without this a counter that counted nothing would pass.
TEST(AllocationCounter, CountsMallocNewAndMatBuffers) {
  if (!cli::allocationCountingAvailable()) GTEST_SKIP() << kNoCounting;
  cli::startCountingAllocations();
  void* volatile p = std::malloc(64);
  std::free(p);
  EXPECT_EQ(cli::stopCountingAllocations(), 1u);
  cli::startCountingAllocations();
  auto* volatile q = new std::vector<int>(1000);
  delete q;
  EXPECT_GE(cli::stopCountingAllocations(), 2u);  // the vector object and its elements
  cli::startCountingAllocations();
  cv::Mat m(480, 640, CV_8UC1);
  EXPECT_GE(cli::stopCountingAllocations(), 1u);
}

struct Counted {
  std::uint64_t allocations = 0;
  int found = 0;
};

// Warms the engine up on the frames twice, then counts a third pass.
Counted countSteadyState(const Settings& settings, const std::vector<Frame>& frames) {
  Engine engine(settings);
  FrameResult r;
  for (int pass = 0; pass < 2; ++pass)
    for (const Frame& f : frames) engine.process(f, r);
  Counted c;
  cli::startCountingAllocations();
  for (const Frame& f : frames) {
    engine.process(f, r);
    c.found += ok(r.status) ? 1 : 0;
  }
  c.allocations = cli::stopCountingAllocations();
  return c;
}

class SteadyState : public testing::TestWithParam<std::tuple<TrackingMode, ContourMode>> {};

TEST_P(SteadyState, AFrameAllocatesNothing) {
  if (!cli::allocationCountingAvailable()) GTEST_SKIP() << kNoCounting;
  cv::setNumThreads(1);  // OpenCV's thread pool would allocate per task
  Settings s = benchSceneSettings({640, 480});
  s.pipeline.tracking.mode = std::get<0>(GetParam());
  s.pipeline.reconstruction.contour_mode = std::get<1>(GetParam());
  const Counted c = countSteadyState(s, benchFrames());
  EXPECT_GE(c.found, kFrames * 3 / 4);  // the pipeline really ran to a pose (the scene hides the target now and then)
  EXPECT_EQ(c.allocations, 0u);
}

INSTANTIATE_TEST_SUITE_P(Modes, SteadyState,
                         testing::Combine(testing::Values(TrackingMode::Off, TrackingMode::Corners2D,
                                                          TrackingMode::Parameters3D),
                                          testing::Values(ContourMode::SubPixel, ContourMode::FullPathMod,
                                                          ContourMode::EightPointsMod)));

// Frames without the target (an empty frame, then one of clutter only) in between:
// the error paths allocate nothing either.
TEST(SteadyStateErrors, LostAndEmptyFramesAllocateNothing) {
  if (!cli::allocationCountingAvailable()) GTEST_SKIP() << kNoCounting;
  cv::setNumThreads(1);
  std::vector<Frame> frames = benchFrames();
  for (std::size_t i = 5; i < frames.size(); i += 7) frames[i].image = cv::Mat::zeros(frames[i].image.size(), CV_8UC1);
  for (std::size_t i = 9; i < frames.size(); i += 11)
    frames[i].image = cv::Mat(frames[i].image.size(), CV_8UC1, cv::Scalar(255));
  Settings s = benchSceneSettings({640, 480});
  s.pipeline.tracking.mode = TrackingMode::Corners2D;
  const Counted c = countSteadyState(s, frames);
  EXPECT_LT(c.found, static_cast<int>(frames.size()));
  EXPECT_EQ(c.allocations, 0u);
}

// A set of four targets, each tracked in its own region, the whole frame searched on its
// cadence: the set's loop allocates nothing either.
TEST(SteadyStateSet, FourTargetsAllocateNothing) {
  if (!cli::allocationCountingAvailable()) GTEST_SKIP() << kNoCounting;
  cv::setNumThreads(1);
  Settings s;
  s.pipeline.tracking.mode = TrackingMode::Corners2D;
  std::vector<TargetGeometry> geometry;
  for (int i = 0; i < 4; ++i) {
    TargetSpec t;
    t.id = i + 1;
    t.geometry.spot_radius_mm = 3.0;
    t.geometry.spot_offset_mm = 10.0 + 10.0 * i;
    s.targets.push_back(t);
    geometry.push_back(t.geometry);
  }
  const cv::Mat background(s.camera().height, s.camera().width, CV_8UC1, cv::Scalar(140));
  std::vector<Frame> frames;
  for (int k = 0; k < kFrames; ++k) {
    std::vector<Pose> poses;
    for (int i = 0; i < 4; ++i)
      poses.push_back(Pose{15.0, 10.0, 4.0 * k, (i % 2 ? 170.0 : -170.0) + 2.0 * k, (i / 2 ? 120.0 : -120.0), 1200.0});
    Frame f;
    composeTargets(background, s.camera(), geometry, TargetLook{}, poses, f.image);
    f.index = k;
    f.timestamp_s = k / 30.0;
    frames.push_back(f);
  }
  const Counted c = countSteadyState(s, frames);
  EXPECT_EQ(c.found, kFrames);
  EXPECT_EQ(c.allocations, 0u);
}

}  // namespace
}  // namespace imagepro
