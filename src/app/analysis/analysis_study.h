#pragma once
// The two case studies of thesis 5.3 as the Analysis window runs them: the drivers are
// the analysis module's (core/analysis/pendulum_study.h, two_target_study.h), the
// ones imagepro-cli's pendulum and two-targets call; the window runs them on a
// background thread and follows them through a StudyProgress.
#include <atomic>

#include "core/analysis/pendulum_study.h"
#include "core/analysis/two_target_study.h"

namespace imagepro::app {

// Shared between the GUI thread and a study running on another thread.
struct StudyProgress {
  std::atomic<int> done{0};
  std::atomic<int> total{0};
  std::atomic<bool> cancel{false};

  // The driver's callbacks that fill this in and read its cancel flag.
  StudyCallbacks callbacks() {
    return {[this](int d, int t) {
              total.store(t);
              done.store(d);
            },
            [this] { return cancel.load(); }};
  }
};

}  // namespace imagepro::app
