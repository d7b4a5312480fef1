#pragma once
// Pacing and measuring the frame loop (thesis 5.2.2: the system keeps up with the
// grabber's 25 Hz at 50-60 % CPU). FramePacer holds a loop to a source's frame rate;
// LoopMeter reports the achieved rate and the share of one core the loop's thread
// used, both over a sliding window of about a second.
#include <chrono>
#include <cstddef>

namespace imagepro {

class FramePacer {
 public:
  // rate_hz <= 0: no pacing (wait() returns at once).
  explicit FramePacer(double rate_hz);
  // Sleeps until the next frame is due. A loop that fell behind is not made to catch
  // up with a burst: the schedule restarts from now.
  void wait();

 private:
  std::chrono::steady_clock::duration period_{};
  std::chrono::steady_clock::time_point next_{};
  bool started_ = false;
};

class LoopMeter {
 public:
  // Call once per frame, from the loop's own thread.
  void tick();
  double hz() const { return hz_; }
  // CPU time of the calling thread over wall time, in percent of one core.
  double cpuPercent() const { return cpu_percent_; }

 private:
  double window_start_wall_ = -1.0;
  double window_start_cpu_ = 0.0;
  std::size_t frames_ = 0;
  double hz_ = 0.0;
  double cpu_percent_ = 0.0;
};

}  // namespace imagepro
