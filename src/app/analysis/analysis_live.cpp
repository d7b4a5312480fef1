#include "app/analysis/analysis_live.h"

namespace imagepro::app {

LiveTwoTargetAnalyser::LiveTwoTargetAnalyser(const Settings& settings)
    : measurer_(settings), thread_([this](std::stop_token stop) { run(stop); }) {}

LiveTwoTargetAnalyser::~LiveTwoTargetAnalyser() { stop(); }

void LiveTwoTargetAnalyser::stop() {
  if (!thread_.joinable()) return;
  thread_.request_stop();
  wake_.notify_all();
  thread_.join();
}

void LiveTwoTargetAnalyser::offer(const QImage& frame, std::int64_t index) {
  {
    std::lock_guard lock(mutex_);
    if (has_pending_) ++skipped_;
    pending_ = frame;  // shares the pixels: the copy to grey happens in the thread
    pending_index_ = index;
    has_pending_ = true;
  }
  wake_.notify_one();
}

void LiveTwoTargetAnalyser::take(std::vector<TwoTargetFrame>& out) {
  std::lock_guard lock(mutex_);
  out.insert(out.end(), done_.begin(), done_.end());
  done_.clear();
}

std::int64_t LiveTwoTargetAnalyser::skipped() const {
  std::lock_guard lock(mutex_);
  return skipped_;
}

bool LiveTwoTargetAnalyser::busy() const {
  std::lock_guard lock(mutex_);
  return has_pending_ || measuring_;
}

void LiveTwoTargetAnalyser::run(std::stop_token stop) {
  QImage grey;
  for (;;) {
    QImage frame;
    std::int64_t index = 0;
    {
      std::unique_lock lock(mutex_);
      if (!wake_.wait(lock, stop, [this] { return has_pending_; })) return;
      frame.swap(pending_);
      index = pending_index_;
      has_pending_ = false;
      measuring_ = true;
    }
    // The packet's image is the grey frame as RGB32 (r = g = b): back to one channel.
    grey = frame.convertToFormat(QImage::Format_Grayscale8);
    const cv::Mat view = grey.isNull() ? cv::Mat()
                                       : cv::Mat(grey.height(), grey.width(), CV_8UC1, grey.bits(),
                                                 static_cast<std::size_t>(grey.bytesPerLine()));
    TwoTargetFrame measured;
    measured.index = index;
    measurer_.measure(view, measured);
    std::lock_guard lock(mutex_);
    done_.push_back(measured);
    measuring_ = false;
  }
}

}  // namespace imagepro::app
