#pragma once
// Live plots of the six parameters over time (Qt Charts), with the ground truth of
// virtual frames beside them; pause freezes the view (recording goes on), export
// writes everything recorded as CSV.
#include <QWidget>

#include <array>
#include <vector>

#include "app/worker/display_packet.h"

class QChart;
class QLineSeries;
class QValueAxis;
class QPushButton;
class QTimer;

namespace imagepro::app {

class PosePlots : public QWidget {
  Q_OBJECT

 public:
  explicit PosePlots(QWidget* parent = nullptr);

  // The recording's bound (about two hours at 25 Hz, 27 MB): past it the oldest tenth
  // goes, so a long run's memory levels off there.
  static constexpr std::size_t kMaxRecorded = 200000;

  void append(const std::vector<PoseSample>& samples);
  void clear();
  bool isPaused() const;
  void setPaused(bool paused);
  const std::vector<PoseSample>& recorded() const { return recorded_; }
  // Writes the recorded samples as pose CSV (+ timestamp and truth columns).
  bool exportCsv(const QString& path, QString& error) const;

 signals:
  void message(const QString& text);
  void error(const QString& text);

 private:
  // The recorded samples on screen: the last kShown, placed by time or frame number.
  struct ShownRange {
    std::size_t first = 0;
    bool timed = false;
    double x0 = 0.0, x1 = 1.0;
    bool few = true;
  };
  ShownRange shownRange() const;
  void redraw();  // every plot at once
  void redrawPlot(int i, const ShownRange& range);
  void exportInteractive();

  struct Plot {
    QChart* chart = nullptr;
    QLineSeries* measured = nullptr;
    QLineSeries* truth = nullptr;
    QValueAxis* x = nullptr;
    QValueAxis* y = nullptr;
  };
  std::array<Plot, 6> plots_;
  std::vector<PoseSample> recorded_;
  QPushButton* pause_;
  QTimer* redraw_timer_;
  bool dirty_ = false;
  int next_plot_ = 0;  // the timer redraws one plot per tick
};

}  // namespace imagepro::app
