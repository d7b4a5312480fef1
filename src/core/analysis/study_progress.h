#pragma once
// Progress and cancellation of the case-study drivers (pendulum_study.h,
// two_target_study.h), which the Analysis window runs on a background thread and the
// CLI in its own: the driver reports after every frame and asks before each one
// whether to stop. Either callback may be left empty.
#include <functional>

namespace imagepro {

struct StudyCallbacks {
  std::function<void(int done, int total)> progress;  // total 0: not known (camera, video)
  std::function<bool()> cancelled;

  void report(int done, int total) const {
    if (progress) progress(done, total);
  }
  bool cancelRequested() const { return cancelled && cancelled(); }
};

}  // namespace imagepro
