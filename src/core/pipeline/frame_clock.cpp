#include "core/pipeline/frame_clock.h"

#include <time.h>

#include <thread>

namespace imagepro {

namespace {

double seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

constexpr double kWindowS = 1.0;

}  // namespace

FramePacer::FramePacer(double rate_hz) {
  if (rate_hz > 0)
    period_ = std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
}

void FramePacer::wait() {
  if (period_.count() == 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (!started_ || now > next_ + period_) {
    started_ = true;
    next_ = now + period_;
    return;
  }
  std::this_thread::sleep_until(next_);
  next_ += period_;
}

void LoopMeter::tick() {
  const double wall = seconds(CLOCK_MONOTONIC);
  const double cpu = seconds(CLOCK_THREAD_CPUTIME_ID);
  if (window_start_wall_ < 0) {
    window_start_wall_ = wall;
    window_start_cpu_ = cpu;
    frames_ = 0;
    return;
  }
  ++frames_;
  const double elapsed = wall - window_start_wall_;
  if (elapsed >= kWindowS) {
    hz_ = static_cast<double>(frames_) / elapsed;
    cpu_percent_ = 100.0 * (cpu - window_start_cpu_) / elapsed;
    window_start_wall_ = wall;
    window_start_cpu_ = cpu;
    frames_ = 0;
  }
}

}  // namespace imagepro
