#pragma once
// Two-target measurement (thesis 5.3.1) of the live stream. The engine of the main
// window reconstructs one target per frame, so the frames themselves are measured
// here: the frames the window shows (their source image, as the display packet
// carries it) go to a thread of their own that reconstructs every target of each,
// with and without distortion correction. Latest frame wins: a frame arriving while
// the previous one is measured replaces any frame still waiting, so the GUI thread
// never waits and no backlog builds.
#include <QImage>

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "app/analysis/analysis_study.h"

namespace imagepro::app {

class LiveTwoTargetAnalyser {
 public:
  explicit LiveTwoTargetAnalyser(const Settings& settings);
  ~LiveTwoTargetAnalyser();  // stop()
  LiveTwoTargetAnalyser(const LiveTwoTargetAnalyser&) = delete;
  LiveTwoTargetAnalyser& operator=(const LiveTwoTargetAnalyser&) = delete;

  // A grey frame (any QImage format whose pixels are grey) with its index.
  void offer(const QImage& frame, std::int64_t index);
  // Moves the frames measured since the last call to the end of `out`.
  void take(std::vector<TwoTargetFrame>& out);
  // Frames replaced before they were measured.
  std::int64_t skipped() const;
  // Ends the thread after the frame in hand (and one still waiting); take() still
  // returns what was measured. Frames offered afterwards are ignored.
  void stop();
  // True while a frame is waiting or being measured.
  bool busy() const;

 private:
  void run(std::stop_token stop);

  TwoTargetMeasurer measurer_;
  mutable std::mutex mutex_;
  std::condition_variable_any wake_;
  QImage pending_;
  std::int64_t pending_index_ = 0;
  bool has_pending_ = false;
  bool measuring_ = false;
  std::int64_t skipped_ = 0;
  std::vector<TwoTargetFrame> done_;
  std::jthread thread_;  // last: starts after everything it uses
};

}  // namespace imagepro::app
