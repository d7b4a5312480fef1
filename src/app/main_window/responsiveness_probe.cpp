#include "app/main_window/responsiveness_probe.h"

#include <QTimer>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "app/main_window/main_window.h"
#include "app/worker/worker.h"

namespace imagepro::app {

namespace {

// The highest frame rate the settings accept: every frame is due at once, so the
// worker renders and processes back to back (its timer still lets queued calls in).
constexpr double kUnpacedHz = 1e6;
// Frames shown before the measurement starts: the first frames build buffers.
constexpr int kWarmUpMs = 300;

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

StallProbe::StallProbe(int interval_ms, QObject* parent)
    : QObject(parent), interval_ms_(std::max(1, interval_ms)), timer_(new QTimer(this)) {
  timer_->setTimerType(Qt::PreciseTimer);
  timer_->setInterval(interval_ms_);
  connect(timer_, &QTimer::timeout, this, [this] {
    const qint64 now = clock_.nsecsElapsed();
    const double cpu = threadCpuMs();
    if (last_ns_ >= 0) {
      gaps_ms_.push_back(static_cast<double>(now - last_ns_) / 1e6);
      gap_cpu_ms_.push_back(cpu - last_cpu_ms_);
    }
    last_ns_ = now;
    last_cpu_ms_ = cpu;
    emit ticked();
  });
}

void StallProbe::start() {
  gaps_ms_.clear();
  gap_cpu_ms_.clear();
  gaps_ms_.reserve(1 << 16);
  gap_cpu_ms_.reserve(1 << 16);
  last_ns_ = -1;
  clock_.start();
  timer_->start();
}

void StallProbe::stop() { timer_->stop(); }

void StallProbe::summarise(ResponsivenessReport& report) const {
  report.interval_ms = interval_ms_;
  report.ticks = ticks();
  report.max_stall_ms = report.p99_stall_ms = report.median_gap_ms = 0.0;
  report.max_stall_cpu_ms = report.max_gap_cpu_ms = 0.0;
  if (gaps_ms_.empty()) return;
  const auto longest = std::max_element(gaps_ms_.begin(), gaps_ms_.end()) - gaps_ms_.begin();
  report.max_stall_cpu_ms = gap_cpu_ms_[static_cast<std::size_t>(longest)];
  report.max_gap_cpu_ms = *std::max_element(gap_cpu_ms_.begin(), gap_cpu_ms_.end());
  std::vector<double> sorted = gaps_ms_;
  std::sort(sorted.begin(), sorted.end());
  const auto at = [&](double q) {
    const auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size()))) - 1;
    return sorted[std::min(i, sorted.size() - 1)];
  };
  report.max_stall_ms = std::max(0.0, sorted.back() - interval_ms_);
  report.p99_stall_ms = std::max(0.0, at(0.99) - interval_ms_);
  report.median_gap_ms = at(0.5);
}

ResponsivenessMeasurement::ResponsivenessMeasurement(MainWindow& window, double seconds, int interval_ms,
                                                     QObject* parent)
    : QObject(parent), window_(window), seconds_(std::max(0.1, seconds)), probe_(interval_ms) {
  // The backlog is sampled at every probe tick and every shown packet.
  connect(&probe_, &StallProbe::ticked, this, &ResponsivenessMeasurement::sampleBacklog);
}

void ResponsivenessMeasurement::start() {
  Settings s = window_.settings();
  s.virtual_scene.frame_rate_hz = kUnpacedHz;
  // A moving target, so tracking and the displays change every frame.
  if (s.virtual_scene.motion.kind == MotionKind::Static) s.virtual_scene.motion.kind = MotionKind::Sinusoid;
  window_.setSettings(s);
  window_.selectSource(SourceKind::Virtual);
  // Counted in the worker thread at the moment each packet is sent.
  connect(window_.worker(), &Worker::packetReady, this, [this] { sent_.fetch_add(1); }, Qt::DirectConnection);
  connect(&window_, &MainWindow::packetShown, this, [this] {
    ++received_;
    if (!started_) {
      started_ = true;
      QTimer::singleShot(kWarmUpMs, this, &ResponsivenessMeasurement::begin);
    }
    sampleBacklog();
  });
  window_.startSource();
}

void ResponsivenessMeasurement::sampleBacklog() {
  if (!clock_.isValid()) return;
  report_.backlog_max = std::max(report_.backlog_max, sent_.load() - received_);
}

void ResponsivenessMeasurement::begin() {
  frames0_ = window_.worker()->framesProcessed();
  shown0_ = window_.packetsShown();
  report_ = ResponsivenessReport{};
  clock_.start();
  probe_.start();
  QTimer::singleShot(static_cast<int>(seconds_ * 1000.0), Qt::PreciseTimer, this, &ResponsivenessMeasurement::end);
}

void ResponsivenessMeasurement::end() {
  probe_.stop();
  report_.seconds = static_cast<double>(clock_.nsecsElapsed()) / 1e9;
  report_.frames_processed = window_.worker()->framesProcessed() - frames0_;
  report_.frames_shown = window_.packetsShown() - shown0_;
  probe_.summarise(report_);
  clock_.invalidate();
  disconnect(window_.worker(), &Worker::packetReady, this, nullptr);
  disconnect(&window_, &MainWindow::packetShown, this, nullptr);
  window_.stopSource();
  done_ = true;
  emit finished();
}

QString formatReport(const ResponsivenessReport& r) {
  const double s = r.seconds > 0.0 ? r.seconds : 1.0;
  QString text;
  text += QStringLiteral("GUI responsiveness: Virtual source unpaced for %1 s, GUI probe timer every %2 ms (%3 ticks)\n")
              .arg(r.seconds, 0, 'f', 1)
              .arg(r.interval_ms)
              .arg(r.ticks);
  text += QStringLiteral("  GUI-thread stall: max %1 ms, 99th percentile %2 ms (goal: none over 50 ms); median tick gap %3 ms\n")
              .arg(r.max_stall_ms, 0, 'f', 1)
              .arg(r.p99_stall_ms, 0, 'f', 1)
              .arg(r.median_gap_ms, 0, 'f', 2);
  text += QStringLiteral("  GUI-thread CPU time: %1 ms within the longest gap; at most %2 ms within any gap\n")
              .arg(r.max_stall_cpu_ms, 0, 'f', 1)
              .arg(r.max_gap_cpu_ms, 0, 'f', 1);
  text += QStringLiteral("  frames processed %1 (%2 /s), frames shown %3 (%4 /s): %5 dropped, not queued\n")
              .arg(r.frames_processed)
              .arg(static_cast<double>(r.frames_processed) / s, 0, 'f', 1)
              .arg(r.frames_shown)
              .arg(static_cast<double>(r.frames_shown) / s, 0, 'f', 1)
              .arg(std::max<std::int64_t>(0, r.frames_processed - r.frames_shown));
  text += QStringLiteral("  backlog: at most %1 packet(s) sent and not yet shown\n").arg(r.backlog_max);
  return text;
}

}  // namespace imagepro::app
