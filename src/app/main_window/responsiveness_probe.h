#pragma once
// Measures the issue's goal "latest frame wins: the GUI never builds a backlog and
// stays responsive (no GUI-thread stall over 50 ms) with the pipeline at full speed".
// A precise GUI-thread timer ticks every few milliseconds; the gap between two ticks
// beyond the interval is the time the GUI thread could not react (a stall). Meanwhile
// the window's Virtual source runs unpaced (as fast as the worker can render and
// process), and the frames processed are compared with the packets the window showed:
// with latest frame wins the difference is dropped, never queued.
#include <QElapsedTimer>
#include <QObject>

#include <atomic>
#include <cstdint>
#include <vector>

class QTimer;

namespace imagepro::app {

class MainWindow;

struct ResponsivenessReport {
  double seconds = 0.0;       // measured wall time
  int interval_ms = 0;        // of the probe timer
  std::int64_t ticks = 0;     // probe ticks seen
  double max_stall_ms = 0.0;  // longest tick gap minus the interval
  double p99_stall_ms = 0.0;  // 99th percentile of (gap - interval), 0 when below
  double median_gap_ms = 0.0;
  // CPU time the GUI thread itself used within a gap: a stall with little of it was
  // spent waiting (for a core, for the display server), not computing.
  double max_stall_cpu_ms = 0.0;  // within the longest gap
  double max_gap_cpu_ms = 0.0;    // the most within any one gap
  std::int64_t frames_processed = 0;  // by the worker during the measurement
  std::int64_t frames_shown = 0;      // packets the window received and showed
  std::int64_t backlog_max = 0;       // most packets sent by the worker and not yet shown, at once
};

// The gaps of a GUI-thread timer.
class StallProbe : public QObject {
  Q_OBJECT

 public:
  explicit StallProbe(int interval_ms, QObject* parent = nullptr);
  void start();
  void stop();
  int intervalMs() const { return interval_ms_; }
  std::int64_t ticks() const { return static_cast<std::int64_t>(gaps_ms_.size()); }
  // Fills every field but the seconds and the frame counts.
  void summarise(ResponsivenessReport& report) const;

 signals:
  void ticked();

 private:
  int interval_ms_;
  QTimer* timer_;
  QElapsedTimer clock_;
  qint64 last_ns_ = -1;
  double last_cpu_ms_ = 0.0;
  std::vector<double> gaps_ms_, gap_cpu_ms_;
};

// Runs the window's Virtual source unpaced for `seconds` with the probe on, then
// emits finished(). The window's settings are changed (frame rate, a moving target).
class ResponsivenessMeasurement : public QObject {
  Q_OBJECT

 public:
  ResponsivenessMeasurement(MainWindow& window, double seconds, int interval_ms = 2, QObject* parent = nullptr);
  void start();
  const ResponsivenessReport& report() const { return report_; }
  bool isDone() const { return done_; }

 signals:
  void finished();

 private:
  void begin();
  void end();
  void sampleBacklog();

  MainWindow& window_;
  double seconds_;
  StallProbe probe_;
  QElapsedTimer clock_;
  std::int64_t frames0_ = 0, shown0_ = 0;
  std::atomic<std::int64_t> sent_{0};  // packets the worker emitted (counted in its thread)
  std::int64_t received_ = 0;          // of those, shown by the window
  ResponsivenessReport report_;
  bool started_ = false, done_ = false;
};

// The report as the lines `imagepro --measure-responsiveness` prints.
QString formatReport(const ResponsivenessReport& report);

}  // namespace imagepro::app
