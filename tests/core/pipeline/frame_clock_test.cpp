#include "core/pipeline/frame_clock.h"

#include <gtest/gtest.h>

#include <time.h>

#include <chrono>

namespace imagepro {
namespace {

TEST(FrameClock, PacerHoldsTheRateAndMeterMeasuresIt) {
  FramePacer pacer(50.0);
  LoopMeter meter;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 61; ++i) {
    pacer.wait();
    meter.tick();
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // 60 periods of 20 ms; sleeping never returns early, a loaded machine may be late.
  EXPECT_GE(elapsed, 1.19);
  EXPECT_NEAR(meter.hz(), 50.0, 10.0);
  // Sleeping costs next to no CPU.
  EXPECT_LT(meter.cpuPercent(), 50.0);
}

TEST(FrameClock, ZeroRateDoesNotPace) {
  FramePacer pacer(0.0);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 1000; ++i) pacer.wait();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
}

// The meter's CPU share agrees with the thread's own clocks over the same window
// (on a shared machine the share itself depends on the load, so it is not fixed here).
TEST(FrameClock, BusyLoopCpuShareMatchesTheThreadClock) {
  auto now = [](clockid_t c) {
    timespec ts{};
    clock_gettime(c, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  };
  LoopMeter meter;
  meter.tick();
  const double wall0 = now(CLOCK_MONOTONIC), cpu0 = now(CLOCK_THREAD_CPUTIME_ID);
  volatile double sink = 0;
  while (meter.hz() == 0.0) {
    for (int k = 0; k < 20000; ++k) sink = sink + k;
    meter.tick();
  }
  const double wall1 = now(CLOCK_MONOTONIC), cpu1 = now(CLOCK_THREAD_CPUTIME_ID);
  const double expected = 100.0 * (cpu1 - cpu0) / (wall1 - wall0);
  EXPECT_NEAR(meter.cpuPercent(), expected, 0.1 * expected + 1.0);
  EXPECT_GT(meter.cpuPercent(), 0.0);
  EXPECT_LE(meter.cpuPercent(), 105.0);
}

}  // namespace
}  // namespace imagepro
